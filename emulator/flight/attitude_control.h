// PX4's multicopter attitude controller (mc_att_control AttitudeControl): quaternion error with
// reduced yaw priority (MC_YAW_WEIGHT), P gains MC_ROLL_P / MC_PITCH_P / MC_YAW_P, yaw-rate
// feed-forward along the world z axis, rates limited to MC_*RATE_MAX.
//   q_red = shortest rotation taking the current thrust axis to the desired one, applied to q
//   q_d'  = q_red (x) (yaw part of q_red^-1 q_d scaled by MC_YAW_WEIGHT)
//   e_FRD = 2 sign(w) vec(q^-1 q_d');  rate_sp_FRD = K e_FRD + R^T (0,0,1) yawspeed_ff
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "emulator/flight/flight_params.h"

namespace hitl::flight {

Eigen::Vector3d attitude_control(const Eigen::Quaterniond& q_FRD_to_NED, const Eigen::Quaterniond& q_sp_FRD_to_NED,
                                 double yawspeed_ff_rad_s, const FlightParams& params);

}  // namespace hitl::flight
