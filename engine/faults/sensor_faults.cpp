#include "engine/faults/sensor_faults.h"

#include <cmath>

#include "engine/model/atmosphere.h"

namespace hitl::faults {
namespace {

constexpr double kWgs84A_m = 6378137.0;
constexpr double kWgs84E2 = 6.69437999014e-3;  ///< first eccentricity squared
constexpr double kDegPerRad = 180.0 / M_PI;

/// Stuck: `held` is taken from the last reading when the fault starts and replaces the value
/// while it lasts; `last` follows what was reported.
template <typename Sample, typename Copy>
void stick(bool stuck, std::optional<Sample>& sample, std::optional<Sample>& last, std::optional<Sample>& held, Copy copy) {
  if (!sample) return;
  if (!stuck) held.reset();
  else {
    if (!held) held = last ? last : sample;
    copy(*held, *sample);
  }
  last = sample;
}

}  // namespace

void offset_lat_lon(double& lat_deg, double& lon_deg, double north_m, double east_m) {
  const double phi = lat_deg / kDegPerRad;
  const double s2 = std::sin(phi) * std::sin(phi);
  const double w = std::sqrt(1.0 - kWgs84E2 * s2);
  const double meridian_m = kWgs84A_m * (1.0 - kWgs84E2) / (w * w * w);  // M: north-south curvature
  const double prime_vertical_m = kWgs84A_m / w;                          // N: east-west curvature
  lat_deg += north_m / meridian_m * kDegPerRad;
  lon_deg += east_m / (prime_vertical_m * std::cos(phi)) * kDegPerRad;
}

void SensorFaults::apply(const ActiveFaults& active, double t_s, sensors::SensorFrame& frame,
                         const std::array<double, 4>& rotor_speed_rad_s) {
  const double dt_s = last_t_s_ >= 0 && t_s > last_t_s_ ? t_s - last_t_s_ : 0.0;
  last_t_s_ = t_s;
  for (std::size_t i = 0; i < rotor_angle_rad_.size(); ++i)
    rotor_angle_rad_[i] = std::fmod(rotor_angle_rad_[i] + rotor_speed_rad_s[i] * dt_s, 2.0 * M_PI);
  if (frame.imu) {
    frame.imu->accel_FRD_m_s2 += active.accel_bias_FRD_m_s2;
    frame.imu->gyro_FRD_rad_s += active.gyro_bias_FRD_rad_s;
    for (const auto& v : active.vibrations) {
      const double phase_rad = 2.0 * M_PI * v.freq_hz * (t_s - v.started_s);
      frame.imu->accel_FRD_m_s2 += v.amp_m_s2 * Eigen::Vector3d(std::cos(phase_rad), std::sin(phase_rad), 0.0);
    }
    for (const auto& r : active.rotor_vibrations) {
      const double phi_rad = rotor_angle_rad_[r.motor];
      frame.imu->accel_FRD_m_s2 += r.amp_m_s2 * Eigen::Vector3d(std::cos(phi_rad), std::sin(phi_rad), 0.0);
    }
    if (active.imu_clip_accel_m_s2 > 0) frame.imu->accel_FRD_m_s2 = frame.imu->accel_FRD_m_s2.cwiseMax(-active.imu_clip_accel_m_s2).cwiseMin(active.imu_clip_accel_m_s2);
    if (active.imu_clip_gyro_rad_s > 0) frame.imu->gyro_FRD_rad_s = frame.imu->gyro_FRD_rad_s.cwiseMax(-active.imu_clip_gyro_rad_s).cwiseMin(active.imu_clip_gyro_rad_s);
  }
  stick(active.imu_stuck, frame.imu, last_imu_, held_imu_, [](const sensors::ImuSample& from, sensors::ImuSample& to) {
    to.accel_FRD_m_s2 = from.accel_FRD_m_s2;
    to.gyro_FRD_rad_s = from.gyro_FRD_rad_s;
  });
  if (frame.mag) frame.mag->mag_FRD_gauss = frame.mag->mag_FRD_gauss * active.mag_scale + active.mag_offset_FRD_gauss;
  stick(active.mag_stuck, frame.mag, last_mag_, held_mag_,
        [](const sensors::MagSample& from, sensors::MagSample& to) { to.mag_FRD_gauss = from.mag_FRD_gauss; });
  if (frame.baro && active.baro_offset_Pa != 0.0) {
    frame.baro->pressure_Pa += active.baro_offset_Pa;
    frame.baro->pressure_alt_m = model::isa_altitude_m(atmosphere_, frame.baro->pressure_Pa);
  }
  stick(active.baro_stuck, frame.baro, last_baro_, held_baro_, [](const sensors::BaroSample& from, sensors::BaroSample& to) {
    to.pressure_Pa = from.pressure_Pa;
    to.pressure_alt_m = from.pressure_alt_m;
    to.temperature_degC = from.temperature_degC;
  });
  if (!frame.gps) return;
  if (active.gps_loss) {
    frame.gps.reset();
    return;
  }
  if (active.gps_north_m != 0.0 || active.gps_east_m != 0.0)
    offset_lat_lon(frame.gps->lat_deg, frame.gps->lon_deg, active.gps_north_m, active.gps_east_m);
  if (!active.gps_drift_NE_m_s.isZero()) {
    frame.gps->v_NED_m_s.head<2>() += active.gps_drift_NE_m_s;
    frame.gps->ground_speed_m_s = frame.gps->v_NED_m_s.head<2>().norm();
    frame.gps->course_over_ground_deg = sensors::course_over_ground_deg(frame.gps->v_NED_m_s);
  }
  if (active.gps_report) {
    frame.gps->fix_type = active.gps_report->fix_type;
    frame.gps->satellites = active.gps_report->satellites;
    frame.gps->eph_m = active.gps_report->eph_m;
    frame.gps->epv_m = active.gps_report->epv_m;
  }
}

}  // namespace hitl::faults
