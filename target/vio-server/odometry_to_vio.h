// MAVLink ODOMETRY -> ModalAI's VIO records: the one place where voxl-hitl-vio-server decides
// frames and units.
//
// What arrives: hitl's ODOMETRY (DESIGN.md §3): pose in frame_id = MAV_FRAME_LOCAL_NED (1),
// q = w,x,y,z rotating body FRD into NED, twist in child_frame_id = MAV_FRAME_BODY_FRD (12),
// covariances as 21-entry upper-right triangles. MAV_FRAME_LOCAL_FRD (20) is accepted for the pose
// too (also gravity aligned, z down); a twist in LOCAL_NED / LOCAL_FRD is rotated into the body.
//
// What voxl-vision-hub expects on hitl_vio (its en_hitl reader, state_manager.c
// hitl_vio_thread, and ModalAI's own ODOMETRY bridge, mavlink_odometry_bridge.cpp):
//   VIO frame = the local NED frame; IMU frame = body FRD (VOXL's common IMU frame)
//   T_imu_wrt_vio   = p_NED_m                      (x, y, z)
//   R_imu_to_vio    = R_FRD_to_NED                 (from q)
//   vel_imu_wrt_vio = v_FRD_m_s, in the BODY frame: vision-hub rotates it into the local frame
//                     itself (v_local = R_imu_to_vio * v), so it must not be rotated here
//   imu_angular_vel = w_FRD_rad_s                  (rollspeed, pitchspeed, yawspeed)
//   pose_covariance / velocity_covariance: the six diagonal entries copied, the rest zero; a
//                     non-finite covariance is "unknown" (NaN first entry, ModalAI's convention)
//   gravity_vector  = (0, 0, +9.80665) m/s^2: gravity points down the NED z axis
//   T_cam_wrt_imu = 0, R_cam_to_imu = identity: there is no camera
//   quality / state = ODOMETRY.quality 1..100 as is (above 100: 100), OK; 0 (unknown) -> 50, OK (the floor of
//                     ModalAI's bridge); -1 (failed) -> -1, FAILED with ERROR_CODE_UNKNOWN
//   frame           = VIO_FRAME_BODY_ALIGNED; timestamp_ns = CLOCK_MONOTONIC when received
//                     (ODOMETRY.time_usec is the simulator's clock, not the board's)
// ext_vio_data_t: the same vio_data_t; last_cam_frame_id counts the ODOMETRY messages published
// (each acts as a "frame"), last_cam_timestamp_ns = timestamp_ns; no features, biases or gravity
// covariance (ground truth has none).
#pragma once

#include <cstdint>

#include "base/common/expected.h"
#include "base/mavlink/messages.h"
#include "target/vio-server/vio_data.h"

namespace hitl::vio {

inline constexpr float kStandardGravity_m_s2 = 9.80665f;
/// Quality published for an ODOMETRY that reports its quality as unknown (0).
inline constexpr int32_t kUnknownQuality = 50;
/// |q| may differ from 1 by this much (float rounding on the sender); q is normalised.
inline constexpr double kQuaternionNormTolerance = 1e-3;

/// The vio_data_t for one ODOMETRY, or why it cannot be published (non-finite pose, twist or
/// quaternion, a quaternion that is not a rotation, or frames it does not know).
Expected<VioData> vio_from_odometry(const mavlink::msg::Odometry& odometry, int64_t timestamp_ns);

/// The ext_vio_data_t carrying `vio`; `frame_id` numbers the published poses.
ExtVioData extended_vio(const VioData& vio, int32_t frame_id);

}  // namespace hitl::vio
