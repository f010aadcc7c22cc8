#include "emulator/flight/attitude_control.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hitl::flight {
namespace {

Eigen::Quaterniond canonical(const Eigen::Quaterniond& q) {
  return q.w() < 0.0 ? Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z()) : q;
}
}  // namespace

Eigen::Vector3d attitude_control(const Eigen::Quaterniond& q_FRD_to_NED, const Eigen::Quaterniond& q_sp_FRD_to_NED,
                                 double yawspeed_ff_rad_s, const FlightParams& params) {
  const Eigen::Quaterniond q = q_FRD_to_NED.normalized();
  Eigen::Quaterniond qd = q_sp_FRD_to_NED.normalized();

  // Reduced attitude: only tilt the thrust axis (body z in NED) onto the desired one.
  const Eigen::Vector3d e_z = q * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d e_z_d = qd * Eigen::Vector3d::UnitZ();
  Eigen::Quaterniond qd_red = Eigen::Quaterniond::FromTwoVectors(e_z, e_z_d);
  if (std::abs(qd_red.x()) > 1.0 - 1e-5 || std::abs(qd_red.y()) > 1.0 - 1e-5) {
    qd_red = qd;  // thrust axes opposite: the full attitude is the only sensible target
  } else {
    qd_red = qd_red * q;
  }
  // Mix in the yaw part scaled by MC_YAW_WEIGHT; the yaw gain is divided by it again, so small yaw
  // errors see MC_YAW_P while large ones yield to roll and pitch.
  const double yaw_w = std::clamp(static_cast<double>(params.MC_YAW_WEIGHT), 0.0, 1.0);
  Eigen::Quaterniond q_mix = canonical(qd_red.inverse() * qd);
  const double w = std::clamp(q_mix.w(), -1.0, 1.0), z = std::clamp(q_mix.z(), -1.0, 1.0);
  q_mix = Eigen::Quaterniond(std::cos(yaw_w * std::acos(w)), 0.0, 0.0, std::sin(yaw_w * std::asin(z)));
  qd = qd_red * q_mix;

  const Eigen::Quaterniond qe = canonical(q.inverse() * qd);
  const Eigen::Vector3d e_FRD = 2.0 * qe.vec();
  const Eigen::Vector3d gain(params.MC_ROLL_P, params.MC_PITCH_P,
                             yaw_w > 1e-4 ? params.MC_YAW_P / yaw_w : static_cast<double>(params.MC_YAW_P));
  Eigen::Vector3d rate_sp = e_FRD.cwiseProduct(gain);
  rate_sp += q.inverse() * Eigen::Vector3d::UnitZ() * yawspeed_ff_rad_s;
  const Eigen::Vector3d rate_max(params.MC_ROLLRATE_MAX * kDegToRad, params.MC_PITCHRATE_MAX * kDegToRad,
                                 params.MC_YAWRATE_MAX * kDegToRad);
  for (int i = 0; i < 3; ++i) rate_sp[i] = std::clamp(rate_sp[i], -rate_max[i], rate_max[i]);
  return rate_sp;
}

}  // namespace hitl::flight
