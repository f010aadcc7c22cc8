#include "emulator/flight/position_control.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "emulator/flight/local_projection.h"

namespace hitl::flight {
namespace {


/// Limits the angle between unit vectors body_z and world_z (PX4 ControlMath::limitTilt).
Eigen::Vector3d limit_tilt(const Eigen::Vector3d& body_z, double max_angle_rad) {
  const Eigen::Vector3d world_z = Eigen::Vector3d::UnitZ();
  const double dot = std::clamp(body_z.dot(world_z), -1.0, 1.0);
  const double angle = std::min(std::acos(dot), max_angle_rad);
  Eigen::Vector3d rejection = body_z - dot * world_z;
  if (rejection.squaredNorm() < 1e-12) rejection = Eigen::Vector3d::UnitX();
  return std::cos(angle) * world_z + std::sin(angle) * rejection.normalized();
}

}  // namespace

Eigen::Quaterniond attitude_from_thrust(const Eigen::Vector3d& thrust_NED, double yaw_rad) {
  Eigen::Vector3d body_z = thrust_NED.norm() > 1e-6 ? Eigen::Vector3d(-thrust_NED.normalized())
                                                     : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d y_c(-std::sin(yaw_rad), std::cos(yaw_rad), 0.0);
  Eigen::Vector3d body_x = y_c.cross(body_z);
  if (body_z.z() < 0.0) body_x = -body_x;
  if (std::abs(body_z.z()) < 1e-6) body_x = Eigen::Vector3d::UnitZ();
  body_x.normalize();
  const Eigen::Vector3d body_y = body_z.cross(body_x);
  Eigen::Matrix3d R_FRD_to_NED;
  R_FRD_to_NED.col(0) = body_x;
  R_FRD_to_NED.col(1) = body_y;
  R_FRD_to_NED.col(2) = body_z;
  return Eigen::Quaterniond(R_FRD_to_NED).normalized();
}

PositionControlOutput PositionControl::update(const PositionSetpoint& sp, const VehicleKinematics& state,
                                              const FlightParams& params, double dt_s, double thrust_max) {
  PositionControlOutput out;
  const double g = kGravity_m_s2;
  const double hover = params.MPC_THR_HOVER;
  const double thr_min = params.MPC_THR_MIN;
  const double thr_max = std::isnan(thrust_max) ? static_cast<double>(params.MPC_THR_MAX) : thrust_max;

  // Position P -> velocity setpoint.
  const Eigen::Vector3d gain_p(params.MPC_XY_P, params.MPC_XY_P, params.MPC_Z_P);
  Eigen::Vector3d v_sp = sp.v_NED_m_s;
  for (int i = 0; i < 3; ++i) {
    if (std::isfinite(sp.p_NED_m[i])) v_sp[i] += gain_p[i] * (sp.p_NED_m[i] - state.p_NED_m[i]);
  }
  const double v_xy = v_sp.head<2>().norm();
  if (v_xy > params.MPC_XY_VEL_MAX) v_sp.head<2>() *= params.MPC_XY_VEL_MAX / v_xy;
  v_sp.z() = std::clamp(v_sp.z(), -static_cast<double>(params.MPC_Z_VEL_MAX_UP),
                        static_cast<double>(params.MPC_Z_VEL_MAX_DN));
  out.v_sp_NED_m_s = v_sp;

  // Velocity PID -> acceleration setpoint.
  const Eigen::Vector3d gain_vp(params.MPC_XY_VEL_P_ACC, params.MPC_XY_VEL_P_ACC, params.MPC_Z_VEL_P_ACC);
  const Eigen::Vector3d gain_vi(params.MPC_XY_VEL_I_ACC, params.MPC_XY_VEL_I_ACC, params.MPC_Z_VEL_I_ACC);
  const Eigen::Vector3d gain_vd(params.MPC_XY_VEL_D_ACC, params.MPC_XY_VEL_D_ACC, params.MPC_Z_VEL_D_ACC);
  Eigen::Vector3d v_err = v_sp - state.v_NED_m_s;
  const Eigen::Vector3d a_sp =
      sp.a_NED_m_s2 + v_err.cwiseProduct(gain_vp) + v_int_NED_m_s2_ - state.a_NED_m_s2.cwiseProduct(gain_vd);
  out.a_sp_NED_m_s2 = a_sp;

  // Acceleration -> thrust vector.
  Eigen::Vector3d body_z = Eigen::Vector3d(-a_sp.x(), -a_sp.y(), g).normalized();
  body_z = limit_tilt(body_z, params.MPC_TILTMAX_AIR * kDegToRad);
  double collective = a_sp.z() * (hover / g) - hover;
  collective /= Eigen::Vector3d::UnitZ().dot(body_z);
  collective = std::min(collective, -thr_min);
  Eigen::Vector3d thr = body_z * collective;

  // Vertical anti-windup: stop integrating into a saturated thrust.
  if ((thr.z() >= -thr_min && v_err.z() >= 0.0) || (thr.z() <= -thr_max && v_err.z() <= 0.0)) v_err.z() = 0.0;

  // Vertical priority with a horizontal margin.
  const double thr_xy_norm = thr.head<2>().norm();
  const double allocated_xy = std::min(thr_xy_norm, static_cast<double>(params.MPC_THR_XY_MARG));
  const double thr_z_max_sq = thr_max * thr_max - allocated_xy * allocated_xy;
  thr.z() = std::max(thr.z(), -std::sqrt(std::max(thr_z_max_sq, 0.0)));
  const double thr_max_xy_sq = thr_max * thr_max - thr.z() * thr.z();
  const double thr_max_xy = thr_max_xy_sq > 0.0 ? std::sqrt(thr_max_xy_sq) : 0.0;
  if (thr_xy_norm > thr_max_xy && thr_xy_norm > 1e-9) thr.head<2>() *= thr_max_xy / thr_xy_norm;

  // Horizontal anti-windup: tracking form on what the limited thrust can produce.
  const Eigen::Vector2d a_xy_produced = thr.head<2>() * (g / hover);
  if (a_sp.head<2>().squaredNorm() > a_xy_produced.squaredNorm() && gain_vp.x() > 0.0) {
    const double arw_gain = 2.0 / gain_vp.x();
    v_err.head<2>() -= arw_gain * (a_sp.head<2>() - a_xy_produced);
  }
  if (freeze_xy_) v_err.head<2>().setZero();
  v_int_NED_m_s2_ += v_err.cwiseProduct(gain_vi) * dt_s;
  v_int_NED_m_s2_.z() = std::clamp(v_int_NED_m_s2_.z(), -g, g);

  out.thrust_NED = thr;
  out.collective_thrust = thr.norm();
  out.q_sp_FRD_to_NED = attitude_from_thrust(thr, sp.yaw_rad);
  return out;
}

}  // namespace hitl::flight
