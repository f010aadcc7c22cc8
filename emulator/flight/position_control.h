// PX4's multicopter position controller (mc_pos_control PositionControl), NED:
//   v_sp   = MPC_*_P (p_sp - p) + v_ff                      (axes with a NaN position: v_ff only)
//            limited to MPC_XY_VEL_MAX, MPC_Z_VEL_MAX_UP / _DN
//   a_sp   = MPC_*_VEL_P_ACC (v_sp - v) + integral - MPC_*_VEL_D_ACC a        + a_ff
//   body_z = normalize(-a_sp_x, -a_sp_y, g), tilt limited to MPC_TILTMAX_AIR
//   thrust = (a_sp_z MPC_THR_HOVER / g - MPC_THR_HOVER) / body_z.z  (normalized, negative = up)
// then vertical priority with a horizontal margin (MPC_THR_XY_MARG), anti-windup on both, and the
// attitude setpoint from the thrust direction and the yaw setpoint.
#pragma once

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "emulator/flight/flight_params.h"

namespace hitl::flight {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct PositionSetpoint {
  Eigen::Vector3d p_NED_m = Eigen::Vector3d::Constant(kNaN);  ///< NaN axis: velocity control
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();        ///< feed-forward / setpoint
  Eigen::Vector3d a_NED_m_s2 = Eigen::Vector3d::Zero();       ///< feed-forward
  double yaw_rad = 0.0;
  double yawspeed_rad_s = 0.0;  ///< feed-forward
};

struct PositionControlOutput {
  Eigen::Vector3d v_sp_NED_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_sp_NED_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d thrust_NED = Eigen::Vector3d::Zero();  ///< normalized thrust vector, z < 0 up
  Eigen::Quaterniond q_sp_FRD_to_NED = Eigen::Quaterniond::Identity();
  double collective_thrust = 0.0;  ///< |thrust_NED|, 0..1
};

struct VehicleKinematics {
  Eigen::Vector3d p_NED_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_NED_m_s2 = Eigen::Vector3d::Zero();
};

class PositionControl {
 public:
  void reset() { v_int_NED_m_s2_.setZero(); }
  /// Horizontal integrator off (on the ground during takeoff: friction would wind it up).
  void freeze_horizontal_integral(bool freeze) { freeze_xy_ = freeze; }
  /// Thrust limit override (landing: ramps down after ground contact); NaN = MPC_THR_MAX.
  PositionControlOutput update(const PositionSetpoint& sp, const VehicleKinematics& state, const FlightParams& params,
                               double dt_s, double thrust_max = kNaN);
  const Eigen::Vector3d& velocity_integral() const { return v_int_NED_m_s2_; }

 private:
  Eigen::Vector3d v_int_NED_m_s2_ = Eigen::Vector3d::Zero();
  bool freeze_xy_ = false;
};

/// Attitude with body z along -thrust_NED and the given yaw (PX4 ControlMath::bodyzToAttitude).
Eigen::Quaterniond attitude_from_thrust(const Eigen::Vector3d& thrust_NED, double yaw_rad);

}  // namespace hitl::flight
