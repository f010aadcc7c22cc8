// What the board's MAVLink receiver hands to target/core: HIL_SENSOR and HIL_GPS as decoded from
// the wire, still in wire units (the adapter copies the decoded message field by field; units
// and frames as in DESIGN.md section 3). Conversions to SI happen in core (hil_split, hil_gps).
#pragma once

#include <cstdint>

namespace hitl::target {

/// A decoded HIL_SENSOR (id 107). Body FRD.
struct HilSensorInput {
  uint64_t time_usec = 0;          ///< sender's time; ignored on the board (stamped on arrival)
  float accel_FRD_m_s2[3] = {};    ///< xacc, yacc, zacc: specific force
  float gyro_FRD_rad_s[3] = {};    ///< xgyro, ygyro, zgyro
  float mag_FRD_gauss[3] = {};     ///< xmag, ymag, zmag
  float abs_pressure_hPa = 0;      ///< hPa on the wire; the board converts to Pa
  float diff_pressure_hPa = 0;     ///< not used by the split (no airspeed sensor on the x500)
  float pressure_alt_m = 0;        ///< not used (PX4 ignores it too)
  float temperature_degC = 0;
  uint32_t fields_updated = 0;     ///< hil_sensor::k* bits
  uint8_t id = 0;                  ///< sensor instance; ignored, as PX4's MavlinkReceiver does
};

/// A decoded HIL_GPS (id 113).
struct HilGpsInput {
  uint64_t time_usec = 0;          ///< copied to time_utc_us
  uint8_t fix_type = 0;            ///< 3 = 3D fix
  int32_t lat_degE7 = 0;
  int32_t lon_degE7 = 0;
  int32_t alt_mm = 0;              ///< MSL; PX4 uses it for the ellipsoid altitude too
  uint16_t eph_cm = 0;             ///< horizontal accuracy, cm (PX4 reads it so, not as DOP)
  uint16_t epv_cm = 0;             ///< vertical accuracy, cm
  uint16_t vel_cm_s = 0;           ///< ground speed
  int16_t vn_cm_s = 0;             ///< velocity north, NED
  int16_t ve_cm_s = 0;             ///< velocity east, NED
  int16_t vd_cm_s = 0;             ///< velocity down, NED
  uint16_t cog_cdeg = 0;           ///< course over ground 0..35999; 65535 = unknown
  uint8_t satellites_visible = 0;
  uint8_t id = 0;                  ///< GPS instance; ignored (one GPS)
};

}  // namespace hitl::target
