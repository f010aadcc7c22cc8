#include "emulator/flight/mixer.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

namespace hitl::flight {

QuadGeometry geometry_from(const FlightParams& p) {
  return {RotorGeometry{p.CA_ROTOR0_PX, p.CA_ROTOR0_PY, p.CA_ROTOR0_KM},
          RotorGeometry{p.CA_ROTOR1_PX, p.CA_ROTOR1_PY, p.CA_ROTOR1_KM},
          RotorGeometry{p.CA_ROTOR2_PX, p.CA_ROTOR2_PY, p.CA_ROTOR2_KM},
          RotorGeometry{p.CA_ROTOR3_PX, p.CA_ROTOR3_PY, p.CA_ROTOR3_KM}};
}

Mixer::Mixer(const QuadGeometry& geometry) : geometry_(geometry) {
  Eigen::Matrix4d B;  // rows: roll, pitch, yaw, thrust; columns: motors
  for (int i = 0; i < 4; ++i) {
    const RotorGeometry& r = geometry[static_cast<std::size_t>(i)];
    B.col(i) << -r.py_FRD_m, r.px_FRD_m, r.km, 1.0;
  }
  mix_ = B.completeOrthogonalDecomposition().pseudoInverse();
  // PX4 normalization.
  const auto rms_scale = [&](int col) {
    int nonzero = 0;
    for (int i = 0; i < 4; ++i) nonzero += std::abs(mix_(i, col)) > 1e-3 ? 1 : 0;
    return nonzero > 0 ? std::sqrt(mix_.col(col).squaredNorm() / (nonzero / 2.0)) : 1.0;
  };
  const double rp_scale = std::max(rms_scale(0), rms_scale(1));
  if (rp_scale > 1e-9) mix_.leftCols<2>() /= rp_scale;
  const double yaw_scale = mix_.col(2).cwiseAbs().maxCoeff();
  if (yaw_scale > 1e-9) mix_.col(2) /= yaw_scale;
  int thrust_nonzero = 0;
  double thrust_sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    thrust_sum += std::abs(mix_(i, 3));
    thrust_nonzero += std::abs(mix_(i, 3)) > 1e-9 ? 1 : 0;
  }
  if (thrust_nonzero > 0) mix_.col(3) /= thrust_sum / thrust_nonzero;
  mix_ = mix_.unaryExpr([](double v) { return std::abs(v) < 1e-6 ? 0.0 : v; });
}

MixerOutput Mixer::mix(const Eigen::Vector3d& torque, double collective, double thr_mdl_fac) const {
  MixerOutput out;
  Eigen::Vector4d rp = mix_.col(0) * torque.x() + mix_.col(1) * torque.y();
  const Eigen::Vector4d yaw = mix_.col(2) * torque.z();
  double thrust = std::clamp(collective, 0.0, 1.0);

  // Roll/pitch must fit in 0..1 around some collective: scale them if their spread is too wide.
  const double spread = rp.maxCoeff() - rp.minCoeff();
  if (spread > 1.0) {
    rp /= spread;
    out.saturated_positive[0] = torque.x() > 0.0;
    out.saturated_negative[0] = torque.x() < 0.0;
    out.saturated_positive[1] = torque.y() > 0.0;
    out.saturated_negative[1] = torque.y() < 0.0;
  }
  // Shift the collective so that roll/pitch fit.
  Eigen::Vector4d t = mix_.col(3) * thrust + rp;
  if (t.maxCoeff() > 1.0) t.array() -= t.maxCoeff() - 1.0;
  if (t.minCoeff() < 0.0) t.array() -= t.minCoeff();

  // Yaw gets what still fits.
  double k = 1.0;
  for (int i = 0; i < 4; ++i) {
    if (yaw[i] > 1e-12) k = std::min(k, (1.0 - t[i]) / yaw[i]);
    if (yaw[i] < -1e-12) k = std::min(k, t[i] / -yaw[i]);
  }
  k = std::clamp(k, 0.0, 1.0);
  if (k < 1.0) {
    out.saturated_positive[2] = torque.z() > 0.0;
    out.saturated_negative[2] = torque.z() < 0.0;
  }
  t += k * yaw;
  for (std::size_t i = 0; i < 4; ++i) {
    out.thrust[i] = std::clamp(t[static_cast<int>(i)], 0.0, 1.0);
    out.u[i] = motor_command_from_thrust(out.thrust[i], thr_mdl_fac);
  }
  return out;
}

double motor_command_from_thrust(double thrust_fraction, double thr_mdl_fac) {
  const double t = std::clamp(thrust_fraction, 0.0, 1.0);
  const double f = std::clamp(thr_mdl_fac, 0.0, 1.0);
  if (f < 1e-6) return t;
  const double a = 1.0 - f;
  return std::clamp((-a + std::sqrt(a * a + 4.0 * f * t)) / (2.0 * f), 0.0, 1.0);
}

}  // namespace hitl::flight
