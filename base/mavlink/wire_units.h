// Unit conversions at the MAVLink boundary, written once (PX4's SimulatorMavlink::update_sensors
// and handle_message_hil_gps are the decoders these invert).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace hitl::mavlink::wire {

inline constexpr uint16_t kCogUnknown = 65535;  ///< HIL_GPS / GPS_RAW_INT cog: not known
inline constexpr uint16_t kUint16Unknown = UINT16_MAX;

/// Pa -> hPa (HIL_SENSOR.abs_pressure / diff_pressure; PX4 multiplies by 100).
inline float Pa_to_hPa(double pressure_Pa) { return static_cast<float>(pressure_Pa / 100.0); }
/// degrees -> degE7 (lat/lon).
inline int32_t deg_to_degE7(double deg) { return static_cast<int32_t>(std::llround(deg * 1e7)); }
/// metres -> millimetres (HIL_GPS.alt).
inline int32_t m_to_mm(double m) { return static_cast<int32_t>(std::llround(m * 1000.0)); }
/// metres -> centimetres, saturated to uint16 (HIL_GPS.eph / epv are accuracies in cm).
inline uint16_t m_to_cm_u16(double m) {
  return static_cast<uint16_t>(std::clamp(std::llround(m * 100.0), 0LL, static_cast<long long>(kUint16Unknown - 1)));
}
/// m/s -> cm/s, signed (HIL_GPS.vn / ve / vd).
inline int16_t m_s_to_cm_s(double v_m_s) {
  return static_cast<int16_t>(std::clamp(std::llround(v_m_s * 100.0), -32767LL, 32767LL));
}
/// m/s -> cm/s, unsigned (HIL_GPS.vel, ground speed).
inline uint16_t m_s_to_cm_s_u16(double v_m_s) {
  return static_cast<uint16_t>(std::clamp(std::llround(v_m_s * 100.0), 0LL, 65534LL));
}
/// degrees 0..360 -> centidegrees 0..35999 (course over ground).
inline uint16_t deg_to_cdeg(double deg) {
  double d = std::fmod(deg, 360.0);
  if (d < 0) d += 360.0;
  return static_cast<uint16_t>(std::llround(d * 100.0) % 36000);
}
/// seconds -> microseconds (time_usec fields).
inline uint64_t s_to_us(double t_s) { return static_cast<uint64_t>(std::llround(t_s * 1e6)); }

}  // namespace hitl::mavlink::wire
