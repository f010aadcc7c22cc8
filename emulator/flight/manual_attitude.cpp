#include "emulator/flight/manual_attitude.h"

#include <algorithm>
#include <cmath>

#include "emulator/flight/attitude_filter.h"

namespace hitl::flight {

double manual_thrust(double throttle_stick, const FlightParams& params) {
  const double t = std::clamp(throttle_stick, 0.0, 1.0);
  const double hover = params.MPC_THR_HOVER;
  if (t <= 0.5) return params.MPC_MANTHR_MIN + (hover - params.MPC_MANTHR_MIN) * (t / 0.5);
  return hover + (params.MPC_THR_MAX - hover) * ((t - 0.5) / 0.5);
}

AttitudeSetpoint ManualAttitudeSetpoint::update(const StickInput& sticks, const FlightParams& params, double dt_s) {
  AttitudeSetpoint sp;
  sp.yawspeed_rad_s = std::clamp(sticks.yaw, -1.0, 1.0) * params.MPC_MAN_Y_MAX * kDegToRad;
  yaw_sp_rad_ = wrap_pi(yaw_sp_rad_ + sp.yawspeed_rad_s * dt_s);

  // Tilt as a rotation vector in the heading frame: roll right about +x, pitch stick forward
  // (nose down) about -y. Its length is limited to MPC_MAN_TILT_MAX.
  Eigen::Vector2d v(std::clamp(sticks.roll, -1.0, 1.0), -std::clamp(sticks.pitch, -1.0, 1.0));
  if (v.norm() > 1.0) v.normalize();
  v *= params.MPC_MAN_TILT_MAX * kDegToRad;
  const double angle = v.norm();
  const Eigen::Quaterniond tilt =
      angle > 1e-9 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d(v.x(), v.y(), 0.0) / angle))
                   : Eigen::Quaterniond::Identity();
  sp.q_sp_FRD_to_NED = (Eigen::Quaterniond(Eigen::AngleAxisd(yaw_sp_rad_, Eigen::Vector3d::UnitZ())) * tilt).normalized();
  sp.collective_thrust = manual_thrust(sticks.throttle, params);
  return sp;
}

}  // namespace hitl::flight
