#include "emulator/flight/manual_setpoint.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "emulator/flight/attitude_filter.h"

namespace hitl::flight {
namespace {
constexpr double kLockSpeed_m_s = 0.3;  // lock the position once braked below this
}  // namespace

double apply_deadzone(double stick, double deadzone) {
  const double s = std::clamp(stick, -1.0, 1.0);
  if (std::abs(s) <= deadzone || deadzone >= 1.0) return 0.0;
  return std::copysign((std::abs(s) - deadzone) / (1.0 - deadzone), s);
}

void ManualPositionSetpoint::reset(const Eigen::Vector3d& p_NED_m, double yaw_rad) {
  v_xy_sp_NED_m_s_.setZero();
  v_z_sp_m_s_ = 0.0;
  hold_NED_m_ = p_NED_m;
  xy_locked_ = z_locked_ = true;
  yaw_sp_rad_ = yaw_rad;
}

bool ManualPositionSetpoint::wants_climb(const StickInput& sticks, const FlightParams& params) {
  return apply_deadzone(2.0 * (sticks.throttle - 0.5), params.MPC_HOLD_DZ) > 0.3;
}

PositionSetpoint ManualPositionSetpoint::update(const StickInput& sticks, const Eigen::Vector3d& p_NED_m,
                                                const Eigen::Vector3d& v_NED_m_s, double yaw_rad,
                                                const FlightParams& params, double dt_s) {
  PositionSetpoint sp;
  const double dz = params.MPC_HOLD_DZ;

  // Horizontal: sticks in the heading frame -> NED velocity, slew-limited.
  Eigen::Vector2d stick_fwd_right(apply_deadzone(sticks.pitch, dz), apply_deadzone(sticks.roll, dz));
  if (stick_fwd_right.norm() > 1.0) stick_fwd_right.normalize();
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const Eigen::Vector2d target_NED =
      params.MPC_VEL_MANUAL * Eigen::Vector2d(c * stick_fwd_right.x() - s * stick_fwd_right.y(),
                                              s * stick_fwd_right.x() + c * stick_fwd_right.y());
  const Eigen::Vector2d dv = target_NED - v_xy_sp_NED_m_s_;
  const double dv_max = params.MPC_ACC_HOR * dt_s;
  v_xy_sp_NED_m_s_ += dv.norm() > dv_max ? Eigen::Vector2d(dv * (dv_max / dv.norm())) : dv;
  const bool xy_centred = stick_fwd_right.isZero();
  if (!xy_centred) xy_locked_ = false;
  if (xy_centred && !xy_locked_ && v_xy_sp_NED_m_s_.norm() < 1e-3 && v_NED_m_s.head<2>().norm() < kLockSpeed_m_s) {
    xy_locked_ = true;
    hold_NED_m_.head<2>() = p_NED_m.head<2>();
  }
  if (xy_locked_) {
    v_xy_sp_NED_m_s_.setZero();
    sp.p_NED_m.head<2>() = hold_NED_m_.head<2>();
  } else {
    sp.v_NED_m_s.head<2>() = v_xy_sp_NED_m_s_;
  }

  // Vertical: throttle around centre -> climb/sink rate.
  const double up = apply_deadzone(2.0 * (sticks.throttle - 0.5), dz);
  const double target_z = up > 0.0 ? -up * params.MPC_Z_VEL_MAX_UP : -up * params.MPC_Z_VEL_MAX_DN;
  const double dvz_max = params.MPC_ACC_UP_MAX * dt_s;
  v_z_sp_m_s_ += std::clamp(target_z - v_z_sp_m_s_, -dvz_max, dvz_max);
  if (up != 0.0) z_locked_ = false;
  if (up == 0.0 && !z_locked_ && std::abs(v_z_sp_m_s_) < 1e-3 && std::abs(v_NED_m_s.z()) < kLockSpeed_m_s) {
    z_locked_ = true;
    hold_NED_m_.z() = p_NED_m.z();
  }
  if (z_locked_) {
    v_z_sp_m_s_ = 0.0;
    sp.p_NED_m.z() = hold_NED_m_.z();
  } else {
    sp.v_NED_m_s.z() = v_z_sp_m_s_;
  }

  // Yaw: stick -> rate, integrated into the heading setpoint.
  const double yaw_rate = apply_deadzone(sticks.yaw, dz) * params.MPC_MAN_Y_MAX * kDegToRad;
  yaw_sp_rad_ = wrap_pi(yaw_sp_rad_ + yaw_rate * dt_s);
  sp.yaw_rad = yaw_sp_rad_;
  sp.yawspeed_rad_s = yaw_rate;
  return sp;
}

}  // namespace hitl::flight
