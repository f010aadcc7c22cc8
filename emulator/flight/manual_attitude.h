// Stabilized-mode stick semantics (PX4 mc_att_control's manual attitude setpoint, v1.14+):
//   roll/pitch   -> a tilt whose rotation vector is (roll, -pitch) x MPC_MAN_TILT_MAX about the
//                   heading frame's axes (pitch stick forward = nose down)
//   yaw          -> yaw rate up to MPC_MAN_Y_MAX, integrated into the heading setpoint
//   throttle     -> collective thrust through PX4's throttle curve (MPC_THR_CURVE 0, "rescale to
//                   hover thrust"): 0..0.5 maps MPC_MANTHR_MIN..MPC_THR_HOVER, 0.5..1 maps
//                   MPC_THR_HOVER..MPC_THR_MAX
// No position or velocity control: the pilot (or `hitl fly trajectory --mode attitude`) closes
// those loops.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "emulator/flight/flight_params.h"
#include "emulator/flight/inputs.h"

namespace hitl::flight {

struct AttitudeSetpoint {
  Eigen::Quaterniond q_sp_FRD_to_NED = Eigen::Quaterniond::Identity();
  double collective_thrust = 0.0;  ///< 0..1
  double yawspeed_rad_s = 0.0;     ///< feed-forward
};

/// PX4's throttle curve for manual thrust (stick 0..1 -> normalized thrust).
double manual_thrust(double throttle_stick, const FlightParams& params);

class ManualAttitudeSetpoint {
 public:
  /// Starts from heading `yaw_rad` (entering Stabilized).
  void reset(double yaw_rad) { yaw_sp_rad_ = yaw_rad; }
  AttitudeSetpoint update(const StickInput& sticks, const FlightParams& params, double dt_s);
  double yaw_sp_rad() const { return yaw_sp_rad_; }

 private:
  double yaw_sp_rad_ = 0.0;
};

}  // namespace hitl::flight
