#include "target/core/hil_gps.h"

#include <cmath>
#include <limits>

#include "base/contract/device_ids.h"

namespace hitl::target {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

float cog_rad_from_cdeg(uint16_t cog_cdeg) {
  if (cog_cdeg == kHilGpsCogUnknown) return kNaN;
  double cog_rad = static_cast<double>(cog_cdeg) * 1e-2 * kPi / 180.0;
  cog_rad = std::fmod(cog_rad, 2.0 * kPi);  // 36000 cdeg and above wrap, as PX4's wrap_2pi
  if (cog_rad < 0.0) cog_rad += 2.0 * kPi;
  return static_cast<float>(cog_rad);
}

SensorGps to_sensor_gps(const HilGpsInput& gps, uint64_t now_us) {
  SensorGps out;
  out.timestamp_us = now_us;
  out.time_utc_us = gps.time_usec;
  out.device_id = kDeviceIdGps;
  out.latitude_deg = gps.lat_degE7 * 1e-7;
  out.longitude_deg = gps.lon_degE7 * 1e-7;
  out.altitude_msl_m = gps.alt_mm * 1e-3;
  out.altitude_ellipsoid_m = out.altitude_msl_m;
  out.s_variance_m_s = 0.25F;
  out.c_variance_rad = 0.5F;
  out.eph_m = static_cast<float>(gps.eph_cm) * 1e-2F;
  out.epv_m = static_cast<float>(gps.epv_cm) * 1e-2F;
  out.vel_m_s = static_cast<float>(gps.vel_cm_s) / 100.0F;
  out.vel_n_m_s = static_cast<float>(gps.vn_cm_s) / 100.0F;
  out.vel_e_m_s = static_cast<float>(gps.ve_cm_s) / 100.0F;
  out.vel_d_m_s = static_cast<float>(gps.vd_cm_s) / 100.0F;
  out.cog_rad = cog_rad_from_cdeg(gps.cog_cdeg);
  out.heading_rad = kNaN;
  out.heading_offset_rad = kNaN;
  out.vel_ned_valid = true;
  out.fix_type = gps.fix_type;
  out.satellites_used = gps.satellites_visible;
  return out;
}

}  // namespace hitl::target
