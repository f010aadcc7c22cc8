// Attitude from gyro, accelerometer and magnetometer: a nonlinear complementary (Mahony) filter
// structured like PX4's attitude_estimator_q.
//   corr_FRD = w_acc (k_FRD x f_FRD/|f|)                     k_FRD = R_FRD_to_NED^T (0,0,1): "down"
//            + w_mag R^T (0, 0, D - heading(R m_FRD))         D: declination; heading of the field
//              or, with the inclination I known (HITL_MAG_INCL): w_mag (m_FRD/|m| x R^T b_NED),
//              b_NED = (cos I cos D, cos I sin D, sin I)
//   b_FRD   -= w_bias corr_FRD dt   (only while turning slower than 10 deg/s; |b| <= ATT_BIAS_MAX)
//   q_FRD_to_NED <- q (x) exp((gyro - b + corr) dt / 2)
// f_FRD is the specific force with the estimated motion acceleration removed (ATT_ACC_COMP): at
// rest it is -g along "down".
#pragma once

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hitl::flight {

struct AttitudeGains {
  double w_acc = 0.2;
  double w_mag = 0.1;
  double w_gyro_bias = 0.1;
  double bias_max_rad_s = 0.05;
  /// Field inclination (down positive); NaN: heading-only magnetometer correction.
  double inclination_rad = std::numeric_limits<double>::quiet_NaN();
};

class AttitudeFilter {
 public:
  /// Roll and pitch from the accelerometer, yaw from the magnetometer and the declination.
  void initialize(const Eigen::Vector3d& accel_FRD_m_s2, const Eigen::Vector3d& mag_FRD_gauss, double declination_rad);
  bool initialized() const { return initialized_; }

  /// One IMU step: corrections from this accel sample and the latest mag sample, then integration.
  /// a_motion_NED_m_s2 is removed from the accelerometer reading (zero when not compensating).
  void update(const Eigen::Vector3d& gyro_FRD_rad_s, const Eigen::Vector3d& accel_FRD_m_s2,
              const Eigen::Vector3d& a_motion_NED_m_s2, double dt_s, const AttitudeGains& gains);
  void set_mag(const Eigen::Vector3d& mag_FRD_gauss, double declination_rad);

  const Eigen::Quaterniond& q_FRD_to_NED() const { return q_FRD_to_NED_; }
  const Eigen::Vector3d& gyro_bias_FRD_rad_s() const { return gyro_bias_FRD_rad_s_; }
  /// Bias-corrected body rates of the last update.
  const Eigen::Vector3d& rates_FRD_rad_s() const { return rates_FRD_rad_s_; }
  /// Heading error the magnetometer sees (declination - measured heading), rad; the last tilt
  /// correction angle from the accelerometer, rad.
  double mag_heading_innovation_rad() const { return mag_innovation_rad_; }
  double accel_tilt_innovation_rad() const { return accel_innovation_rad_; }

 private:
  double heading_error_rad(const Eigen::Vector3d& mag_FRD_gauss, double declination_rad) const;

  bool initialized_ = false;
  Eigen::Quaterniond q_FRD_to_NED_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d gyro_bias_FRD_rad_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d rates_FRD_rad_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d mag_FRD_gauss_ = Eigen::Vector3d::Zero();
  bool have_mag_ = false;
  double declination_rad_ = 0.0;
  double mag_innovation_rad_ = 0.0;
  double accel_innovation_rad_ = 0.0;
};

/// Wraps an angle to (-pi, pi].
double wrap_pi(double angle_rad);

}  // namespace hitl::flight
