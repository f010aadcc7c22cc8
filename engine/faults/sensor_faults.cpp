#include "engine/faults/sensor_faults.h"

#include <cmath>

#include "engine/model/atmosphere.h"

namespace hitl::faults {
namespace {

constexpr double kWgs84A_m = 6378137.0;
constexpr double kWgs84E2 = 6.69437999014e-3;  ///< first eccentricity squared
constexpr double kDegPerRad = 180.0 / M_PI;

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

void apply_sensor_faults(const ActiveFaults& active, const model::AtmosphereConfig& atmosphere, sensors::SensorFrame& frame) {
  if (frame.imu) {
    frame.imu->accel_FRD_m_s2 += active.accel_bias_FRD_m_s2;
    frame.imu->gyro_FRD_rad_s += active.gyro_bias_FRD_rad_s;
  }
  if (frame.mag) frame.mag->mag_FRD_gauss += active.mag_offset_FRD_gauss;
  if (frame.baro && active.baro_offset_Pa != 0.0) {
    frame.baro->pressure_Pa += active.baro_offset_Pa;
    frame.baro->pressure_alt_m = model::isa_altitude_m(atmosphere, frame.baro->pressure_Pa);
  }
  if (!frame.gps) return;
  if (active.gps_loss) {
    frame.gps.reset();
    return;
  }
  if (active.gps_north_m != 0.0 || active.gps_east_m != 0.0)
    offset_lat_lon(frame.gps->lat_deg, frame.gps->lon_deg, active.gps_north_m, active.gps_east_m);
  if (active.gps_report) {
    frame.gps->fix_type = active.gps_report->fix_type;
    frame.gps->satellites = active.gps_report->satellites;
    frame.gps->eph_m = active.gps_report->eph_m;
    frame.gps->epv_m = active.gps_report->epv_m;
  }
}

}  // namespace hitl::faults
