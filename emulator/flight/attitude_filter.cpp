#include "emulator/flight/attitude_filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hitl::flight {

double wrap_pi(double angle_rad) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  angle_rad = std::fmod(angle_rad + std::numbers::pi, two_pi);
  if (angle_rad <= 0.0) angle_rad += two_pi;
  return angle_rad - std::numbers::pi;
}

void AttitudeFilter::initialize(const Eigen::Vector3d& accel_FRD_m_s2, const Eigen::Vector3d& mag_FRD_gauss,
                                double declination_rad) {
  // "Down" in FRD is the negative specific force at rest.
  const Eigen::Vector3d down_FRD = -accel_FRD_m_s2.normalized();
  const double roll_rad = std::atan2(down_FRD.y(), down_FRD.z());
  const double pitch_rad = std::asin(std::clamp(-down_FRD.x(), -1.0, 1.0));
  const Eigen::Quaterniond q_tilt = Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX());
  // The field in the levelled frame; its heading there is the declination minus the yaw.
  const Eigen::Vector3d mag_level = q_tilt * mag_FRD_gauss;
  const double yaw_rad = wrap_pi(declination_rad - std::atan2(mag_level.y(), mag_level.x()));
  q_FRD_to_NED_ = (Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * q_tilt).normalized();
  gyro_bias_FRD_rad_s_.setZero();
  mag_FRD_gauss_ = mag_FRD_gauss;
  have_mag_ = true;
  declination_rad_ = declination_rad;
  initialized_ = true;
}

void AttitudeFilter::set_mag(const Eigen::Vector3d& mag_FRD_gauss, double declination_rad) {
  mag_FRD_gauss_ = mag_FRD_gauss;
  declination_rad_ = declination_rad;
  have_mag_ = mag_FRD_gauss.norm() > 1e-6;
}

double AttitudeFilter::heading_error_rad(const Eigen::Vector3d& mag_FRD_gauss, double declination_rad) const {
  const Eigen::Vector3d mag_NED = q_FRD_to_NED_ * mag_FRD_gauss;
  return wrap_pi(declination_rad - std::atan2(mag_NED.y(), mag_NED.x()));
}

void AttitudeFilter::update(const Eigen::Vector3d& gyro_FRD_rad_s, const Eigen::Vector3d& accel_FRD_m_s2,
                            const Eigen::Vector3d& a_motion_NED_m_s2, double dt_s, const AttitudeGains& gains) {
  if (!initialized_ || dt_s <= 0.0) return;
  const Eigen::Matrix3d R_FRD_to_NED = q_FRD_to_NED_.toRotationMatrix();
  Eigen::Vector3d corr_FRD = Eigen::Vector3d::Zero();

  // Accelerometer: align the estimated "down" with the measured one.
  const Eigen::Vector3d f_FRD = accel_FRD_m_s2 - R_FRD_to_NED.transpose() * a_motion_NED_m_s2;
  const double f_norm = f_FRD.norm();
  if (f_norm > 0.5 * 9.80665 && f_norm < 1.5 * 9.80665) {
    const Eigen::Vector3d down_est_FRD = R_FRD_to_NED.transpose() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d e_FRD = down_est_FRD.cross(f_FRD / f_norm);
    accel_innovation_rad_ = std::asin(std::min(1.0, e_FRD.norm()));
    corr_FRD += gains.w_acc * e_FRD;
  }

  // Magnetometer: heading only, as a rotation about NED down expressed in FRD; or, with a known
  // inclination, the whole field direction (which also levels: the tilt an accelerometer bias
  // causes leaks into the heading through the field's vertical part otherwise).
  if (have_mag_) {
    mag_innovation_rad_ = heading_error_rad(mag_FRD_gauss_, declination_rad_);
    if (std::isfinite(gains.inclination_rad) && mag_FRD_gauss_.norm() > 1e-6) {
      const double ci = std::cos(gains.inclination_rad);
      const Eigen::Vector3d ref_NED(ci * std::cos(declination_rad_), ci * std::sin(declination_rad_),
                                    std::sin(gains.inclination_rad));
      const Eigen::Vector3d e_FRD = mag_FRD_gauss_.normalized().cross(R_FRD_to_NED.transpose() * ref_NED);
      corr_FRD += gains.w_mag * e_FRD;
    } else {
      corr_FRD += R_FRD_to_NED.transpose() * Eigen::Vector3d(0.0, 0.0, gains.w_mag * mag_innovation_rad_);
    }
  }

  // Gyro bias: learn only while turning slowly (large rates make the corrections unreliable).
  constexpr double kBiasLearnMaxRate_rad_s = 0.175;
  if (gyro_FRD_rad_s.norm() < kBiasLearnMaxRate_rad_s) {
    gyro_bias_FRD_rad_s_ -= corr_FRD * (gains.w_gyro_bias * dt_s);
    for (int i = 0; i < 3; ++i) {
      gyro_bias_FRD_rad_s_[i] = std::clamp(gyro_bias_FRD_rad_s_[i], -gains.bias_max_rad_s, gains.bias_max_rad_s);
    }
  }
  rates_FRD_rad_s_ = gyro_FRD_rad_s - gyro_bias_FRD_rad_s_;

  const Eigen::Vector3d w_FRD = rates_FRD_rad_s_ + corr_FRD;
  const double angle_rad = w_FRD.norm() * dt_s;
  if (angle_rad > 1e-12) {
    q_FRD_to_NED_ = (q_FRD_to_NED_ * Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, w_FRD.normalized())));
  }
  q_FRD_to_NED_.normalize();
}

}  // namespace hitl::flight
