// The PX4 topics target/core produces, reduced to the fields it fills, named with units. The PX4
// adapter copies each into the generated struct (sensor_accel_s, sensor_gyro_s, sensor_mag_s,
// sensor_baro_s, sensor_gps_s, battery_status_s) zero-initialised, the field beside each comment;
// the emulator uses them as they are.
#pragma once

#include <cstdint>

namespace hitl::target {

/// sensor_accel (samples = 1, error_count = 0, clip_counter = 0).
struct SensorAccel {
  uint64_t timestamp_us = 0;          ///< timestamp
  uint64_t timestamp_sample_us = 0;   ///< timestamp_sample
  uint32_t device_id = 0;             ///< device_id
  float accel_FRD_m_s2[3] = {};       ///< x, y, z
  float temperature_degC = 0;         ///< temperature
};

/// sensor_gyro (samples = 1, error_count = 0).
struct SensorGyro {
  uint64_t timestamp_us = 0;          ///< timestamp
  uint64_t timestamp_sample_us = 0;   ///< timestamp_sample
  uint32_t device_id = 0;             ///< device_id
  float gyro_FRD_rad_s[3] = {};       ///< x, y, z
  float temperature_degC = 0;         ///< temperature
};

/// sensor_mag (error_count = 0, is_external = false).
struct SensorMag {
  uint64_t timestamp_us = 0;          ///< timestamp
  uint64_t timestamp_sample_us = 0;   ///< timestamp_sample
  uint32_t device_id = 0;             ///< device_id
  float mag_FRD_gauss[3] = {};        ///< x, y, z
  float temperature_degC = 0;         ///< temperature
};

/// sensor_baro (error_count = 0).
struct SensorBaro {
  uint64_t timestamp_us = 0;          ///< timestamp
  uint64_t timestamp_sample_us = 0;   ///< timestamp_sample
  uint32_t device_id = 0;             ///< device_id
  float pressure_Pa = 0;              ///< pressure
  float temperature_degC = 0;         ///< temperature
};

/// sensor_gps, the fields PX4's MavlinkReceiver::handle_message_hil_gps sets; hdop, vdop,
/// noise, jamming and spoofing fields stay 0.
struct SensorGps {
  uint64_t timestamp_us = 0;          ///< timestamp (arrival on the board)
  uint64_t time_utc_us = 0;           ///< time_utc_usec (HIL_GPS.time_usec as sent)
  uint32_t device_id = 0;             ///< device_id
  double latitude_deg = 0;            ///< latitude_deg
  double longitude_deg = 0;           ///< longitude_deg
  double altitude_msl_m = 0;          ///< altitude_msl_m
  double altitude_ellipsoid_m = 0;    ///< altitude_ellipsoid_m (= MSL, as PX4 does for HIL)
  float s_variance_m_s = 0;           ///< s_variance_m_s
  float c_variance_rad = 0;           ///< c_variance_rad
  float eph_m = 0;                    ///< eph
  float epv_m = 0;                    ///< epv
  float vel_m_s = 0;                  ///< vel_m_s
  float vel_n_m_s = 0;                ///< vel_n_m_s
  float vel_e_m_s = 0;                ///< vel_e_m_s
  float vel_d_m_s = 0;                ///< vel_d_m_s
  float cog_rad = 0;                  ///< cog_rad, 0..2pi; NaN when unknown
  float heading_rad = 0;              ///< heading (NaN: no GPS yaw)
  float heading_offset_rad = 0;       ///< heading_offset (NaN)
  bool vel_ned_valid = false;         ///< vel_ned_valid
  uint8_t fix_type = 0;               ///< fix_type
  uint8_t satellites_used = 0;        ///< satellites_used (HIL_GPS.satellites_visible)
};

/// battery_status, the fields a PX4 consumer (commander's battery checks, MAVLink
/// BATTERY_STATUS / SYS_STATUS) reads.
struct BatteryStatus {
  uint64_t timestamp_us = 0;          ///< timestamp
  bool connected = false;             ///< connected
  float voltage_V = 0;                ///< voltage_v
  float current_A = 0;                ///< current_a
  float current_average_A = 0;        ///< current_average_a
  float discharged_mAh = 0;           ///< discharged_mah
  float remaining_ratio = 0;          ///< remaining, 0..1
  float scale = 0;                    ///< scale (>= 1, 1 = no throttle compensation)
  float time_remaining_s = 0;         ///< time_remaining_s (NaN = unknown)
  float temperature_degC = 0;         ///< temperature (NaN = unknown)
  uint8_t cell_count = 0;             ///< cell_count
  uint8_t source = 0;                 ///< source (0 = power module)
  uint8_t id = 0;                     ///< id (1-based)
  uint8_t warning = 0;                ///< warning (0 = BATTERY_WARNING_NONE)
};

}  // namespace hitl::target
