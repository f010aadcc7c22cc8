// HIL_SENSOR.fields_updated: which values a HIL_SENSOR carries fresh (HIL_SENSOR_UPDATED_FLAGS),
// and the groups PX4 reads them in (a group counts only when all its bits are set).
#pragma once

#include <cstdint>
#include <string>

namespace hitl::mavlink::hil_sensor {

inline constexpr uint32_t kXAcc = 1U << 0;
inline constexpr uint32_t kYAcc = 1U << 1;
inline constexpr uint32_t kZAcc = 1U << 2;
inline constexpr uint32_t kXGyro = 1U << 3;
inline constexpr uint32_t kYGyro = 1U << 4;
inline constexpr uint32_t kZGyro = 1U << 5;
inline constexpr uint32_t kXMag = 1U << 6;
inline constexpr uint32_t kYMag = 1U << 7;
inline constexpr uint32_t kZMag = 1U << 8;
inline constexpr uint32_t kAbsPressure = 1U << 9;
inline constexpr uint32_t kDiffPressure = 1U << 10;
inline constexpr uint32_t kPressureAlt = 1U << 11;
inline constexpr uint32_t kTemperature = 1U << 12;
inline constexpr uint32_t kReset = 1U << 31;  ///< full reset of attitude/position/velocities

/// PX4 SimulatorMavlink / MavlinkReceiver groups.
inline constexpr uint32_t kAccel = kXAcc | kYAcc | kZAcc;          // 0x007
inline constexpr uint32_t kGyro = kXGyro | kYGyro | kZGyro;        // 0x038
inline constexpr uint32_t kMag = kXMag | kYMag | kZMag;            // 0x1C0
inline constexpr uint32_t kBaro = kAbsPressure | kPressureAlt | kTemperature;  // 0x1A00

/// True when `fields_updated` carries every bit of `group`.
constexpr bool has_group(uint32_t fields_updated, uint32_t group) { return (fields_updated & group) == group; }

/// Names the sensors a fields_updated value carries: whole groups by name ("accel gyro mag baro"),
/// stray bits of incomplete groups by field ("zmag(partial)").
std::string describe_fields_updated(uint32_t fields_updated);

}  // namespace hitl::mavlink::hil_sensor
