// Position-mode stick semantics (PX4 FlightTaskManualPosition, "simple" stick mapping):
//   roll/pitch beyond MPC_HOLD_DZ -> horizontal velocity in the heading frame, up to MPC_VEL_MANUAL,
//                                    slewed at MPC_ACC_HOR
//   throttle around 0.5 beyond MPC_HOLD_DZ -> vertical velocity up to MPC_Z_VEL_MAX_UP / _DN,
//                                    slewed at MPC_ACC_UP_MAX
//   yaw beyond the deadzone -> yaw rate up to MPC_MAN_Y_MAX
//   centred sticks: the velocity setpoint brakes to zero, then the position (per axis: horizontal,
//   vertical) is locked where the vehicle is and held.
#pragma once

#include <Eigen/Core>

#include "emulator/flight/flight_params.h"
#include "emulator/flight/inputs.h"
#include "emulator/flight/position_control.h"

namespace hitl::flight {

/// A stick value with the deadzone removed and the rest rescaled to -1..1.
double apply_deadzone(double stick, double deadzone);

class ManualPositionSetpoint {
 public:
  /// Starts holding `p_NED_m` with heading `yaw_rad` (entering position mode).
  void reset(const Eigen::Vector3d& p_NED_m, double yaw_rad);
  PositionSetpoint update(const StickInput& sticks, const Eigen::Vector3d& p_NED_m, const Eigen::Vector3d& v_NED_m_s,
                          double yaw_rad, const FlightParams& params, double dt_s);
  /// Throttle asks to climb (takeoff from the ground in position mode).
  static bool wants_climb(const StickInput& sticks, const FlightParams& params);

 private:
  Eigen::Vector2d v_xy_sp_NED_m_s_ = Eigen::Vector2d::Zero();
  double v_z_sp_m_s_ = 0.0;
  Eigen::Vector3d hold_NED_m_ = Eigen::Vector3d::Zero();
  bool xy_locked_ = true, z_locked_ = true;
  double yaw_sp_rad_ = 0.0;
};

}  // namespace hitl::flight
