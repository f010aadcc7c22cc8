// What the estimator reports: the numbers behind ATTITUDE, ATTITUDE_QUATERNION, LOCAL_POSITION_NED,
// GLOBAL_POSITION_INT and ESTIMATOR_STATUS, and the arming check's verdict.
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "base/mavlink/enums.h"

namespace hitl::flight {

/// MAVLink ESTIMATOR_STATUS_FLAGS (common.xml): the codec's constants (std-only, header only).
namespace estimator_flags = ::hitl::mavlink::estimator_status;

/// The state estimate at the last IMU sample.
struct Estimate {
  std::uint64_t time_us = 0;
  Eigen::Quaterniond q_FRD_to_NED = Eigen::Quaterniond::Identity();
  double roll_rad = 0.0, pitch_rad = 0.0, yaw_rad = 0.0;  ///< z-y-x Euler of q_FRD_to_NED
  Eigen::Vector3d w_FRD_rad_s = Eigen::Vector3d::Zero();    ///< gyro minus estimated bias
  Eigen::Vector3d p_NED_m = Eigen::Vector3d::Zero();        ///< from the origin (first good GPS fix, baro ground level)
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_NED_m_s2 = Eigen::Vector3d::Zero();     ///< kinematic acceleration (gravity removed), low-passed
  bool attitude_valid = false;
  bool xy_valid = false, z_valid = false, v_xy_valid = false, v_z_valid = false;
  bool global_valid = false;  ///< origin set: lat/lon/alt meaningful
  double lat_deg = 0.0, lon_deg = 0.0, alt_msl_m = 0.0;
  double origin_lat_deg = 0.0, origin_lon_deg = 0.0, origin_alt_msl_m = 0.0;
  double eph_m = 99.0, epv_m = 99.0, evh_m_s = 99.0, evv_m_s = 99.0;  ///< 1-sigma accuracies
  Eigen::Vector3d gyro_bias_FRD_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_NED_m_s2 = Eigen::Vector3d::Zero();
};

/// ESTIMATOR_STATUS. Test ratios: innovation^2 / (gate^2 * innovation variance); < 1 passes.
struct EstimatorStatus {
  std::uint64_t time_us = 0;
  std::uint16_t flags = 0;
  double vel_ratio = 0.0;
  double pos_horiz_ratio = 0.0;
  double pos_vert_ratio = 0.0;
  double mag_ratio = 0.0;
  double hagl_ratio = 0.0;  ///< no range finder: 0
  double tas_ratio = 0.0;   ///< no airspeed: 0
  double pos_horiz_accuracy_m = 0.0;
  double pos_vert_accuracy_m = 0.0;
};

/// The estimator part of the preflight check; `reason` is PX4-like ("Preflight Fail: ...").
struct Readiness {
  bool ready = false;
  std::string reason;
};

}  // namespace hitl::flight
