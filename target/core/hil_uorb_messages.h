// The two uORB messages the apps processor publishes and MUORB carries to the DSP, field for
// field as the spec's HilSensorImu.msg and HilSensorMagBaro.msg (same names, types and order;
// uint64 -> uint64_t, float32 -> float, uint8 -> uint8_t). The PX4 adapter copies them to and
// from the generated hil_sensor_imu_s / hil_sensor_mag_baro_s member by member.
#pragma once

#include <cstdint>

namespace hitl::target {

/// hil_sensor_imu: published every 4000 us on the apps processor.
struct HilSensorImu {
  uint64_t timestamp = 0;              ///< time since system start (microseconds)
  float accelerometer_m_s2[3] = {};    ///< acceleration in body FRD frame (m/s^2)
  float gyroscope_rad_s[3] = {};       ///< angular velocity in body FRD frame (rad/s)
  float temperature = 0;               ///< temperature (Celsius)
};

/// hil_sensor_mag_baro: published every 10000 us; fields_updated says which part is new.
struct HilSensorMagBaro {
  uint64_t timestamp = 0;              ///< time since system start (microseconds)
  float magnetometer_ga[3] = {};       ///< magnetic field in body FRD frame (Gauss)
  float pressure_pa = 0;               ///< absolute pressure (Pa)
  float temperature = 0;               ///< temperature (Celsius)
  uint8_t fields_updated = 0;          ///< bitmask: bit 0 = mag, bit 1 = baro

  static constexpr uint8_t FIELD_MAG = 1;
  static constexpr uint8_t FIELD_BARO = 2;
};

}  // namespace hitl::target
