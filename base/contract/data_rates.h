// The spec's "Data Flow Rates", once, for host, board and PX4 alike: the simulator's step, what
// it sends, what the board answers with, and the periods of the board's HIL split.
#pragma once

#include <cstdint>

namespace hitl {

inline constexpr double kStepPeriod_s = 0.004;           ///< physics step and HIL_SENSOR period (250 Hz)
inline constexpr double kVioRate_hz = 250.0;             ///< ODOMETRY to voxl-hitl-vio-server
inline constexpr double kActuatorStreamRate_hz = 200.0;  ///< HIL_ACTUATOR_CONTROLS from the board outside lockstep
inline constexpr uint64_t kActuatorStreamPeriod_us = static_cast<uint64_t>(1e6 / kActuatorStreamRate_hz);

/// The apps processor's HIL split (target/core/hil_split.h).
inline constexpr uint64_t kHilImuPublishPeriod_us = 4000;        ///< hil_sensor_imu (HIL_IMU_PUBLISH_INTERVAL_US, 250 Hz)
inline constexpr uint64_t kHilMagBaroPublishPeriod_us = 10000;   ///< hil_sensor_mag_baro (100 Hz)
inline constexpr uint64_t kSimBatteryPeriod_us = 100000;         ///< battery_status (10 Hz)

/// sensor_mag and sensor_baro as the spec's table gives them: what the board publishes when its
/// simulator sends the magnetometer and barometer at these rates (the x500's defaults do).
inline constexpr double kSpecMagRate_hz = 50.0;
inline constexpr double kSpecBaroRate_hz = 10.0;

/// Hz from a period in microseconds.
constexpr double rate_hz_from_period_us(uint64_t period_us) { return 1e6 / static_cast<double>(period_us); }

}  // namespace hitl
