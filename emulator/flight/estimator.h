// The state estimator: attitude (AttitudeFilter) and position/velocity in local NED (three
// AxisFilters) from the sensors only. Each IMU sample predicts (accelerometer rotated to NED,
// gravity removed); GPS (position on a tangent plane around the origin, and velocity), baro (ISA
// altitude relative to its first second's mean) and magnetometer (heading) correct.
//
// The origin is the first GPS fix that has passed the quality checks (3D, eph <= EKF2_REQ_EPH,
// satellites >= EKF2_REQ_NSATS) for 1 s; "position valid" (POS_HORIZ_ABS) needs GPS fused for
// EKF2_REQ_GPS_H with its test ratio passing. Before the origin the horizontal estimate is held at
// zero (CONST_POS_MODE). Height comes from the baro (PX4's default height reference); GPS altitude
// only sets the origin's AMSL altitude.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "emulator/flight/attitude_filter.h"
#include "emulator/flight/axis_filter.h"
#include "emulator/flight/estimator_status.h"
#include "emulator/flight/flight_params.h"
#include "emulator/flight/inputs.h"
#include "emulator/flight/local_projection.h"

namespace hitl::flight {

class Estimator {
 public:
  /// `params` is read at every call (changes apply at once) and must outlive the estimator.
  explicit Estimator(const FlightParams& params) : params_(params) {}

  void handle_imu(const ImuSample& sample);
  void handle_mag(const MagSample& sample);
  void handle_baro(const BaroSample& sample);
  void handle_gps(const GpsSample& sample);
  /// Armed: in-flight gains (ATT_W_*) and motion-acceleration compensation; disarmed: gains times
  /// HITL_ATT_ALIGN (fast levelling and gyro-bias learning on the ground).
  void set_armed(bool armed) { armed_ = armed; }

  const Estimate& estimate() const { return estimate_; }
  EstimatorStatus status() const;
  /// The estimator's preflight checks, worst-first as PX4 reports them.
  Readiness preflight_check() const;
  /// `ekf2 status`-style lines.
  std::vector<std::string> status_lines() const;

 private:
  bool recent(std::uint64_t t_us, double window_s) const;
  double age_s(std::uint64_t t_us) const;
  void update_motion_acceleration(const GpsSample& sample);
  void publish();

  const FlightParams& params_;
  bool armed_ = false;
  std::uint64_t now_us_ = 0;

  AttitudeFilter attitude_;
  std::uint64_t attitude_init_us_ = 0;
  bool have_accel_ = false;
  Eigen::Vector3d last_accel_FRD_m_s2_ = Eigen::Vector3d::Zero();
  std::uint64_t last_imu_us_ = 0, last_mag_us_ = 0, last_baro_us_ = 0, last_gps_us_ = 0;
  std::uint64_t last_clip_us_ = 0;
  bool imu_seen_ = false, mag_seen_ = false, baro_seen_ = false, gps_seen_ = false, clip_seen_ = false;

  AxisFilter axis_[3];  ///< N, E, D
  // Baro: reference from the mean of the first samples.
  int baro_ref_count_ = 0;
  double baro_ref_sum_m_ = 0.0;
  double baro_ref_m_ = 0.0;
  bool z_initialized_ = false;
  // GPS
  GpsSample last_gps_;
  std::uint64_t gps_checks_pass_since_us_ = 0;
  bool gps_checks_passing_ = false;
  LocalProjection projection_;
  double origin_alt_msl_m_ = 0.0;
  std::uint64_t gps_fusing_since_us_ = 0;
  std::uint64_t last_gps_fused_us_ = 0;
  std::uint64_t last_gps_rejected_us_ = 0;
  std::uint64_t gps_pos_rejected_since_us_ = 0;
  bool gps_rejecting_ = false;
  std::deque<std::pair<std::uint64_t, Eigen::Vector3d>> gps_velocity_history_;
  Eigen::Vector3d a_motion_NED_m_s2_ = Eigen::Vector3d::Zero();
  // Test ratios (latest) and innovations
  double vel_ratio_ = 0.0, pos_horiz_ratio_ = 0.0, pos_vert_ratio_ = 0.0, mag_ratio_ = 0.0;
  Eigen::Vector3d a_NED_filtered_m_s2_ = Eigen::Vector3d::Zero();

  Estimate estimate_;
};

}  // namespace hitl::flight
