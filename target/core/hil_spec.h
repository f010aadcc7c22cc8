// The spec's fixed HIL link facts, once: the rates the board's HIL split publishes and its HIL
// instance streams back outside lockstep (DESIGN.md "Data Flow Rates"), and the actuator flags the
// VOXL2 sends. The simulator's own sensor rates are configuration (engine/model's SensorsConfig).
#pragma once

#include <cstdint>

namespace hitl {

/// HIL_IMU_PUBLISH_INTERVAL_US: the split publishes hil_sensor_imu every 4000 us (250 Hz); it is also
/// the simulator's default step, so one HIL_SENSOR per period.
inline constexpr uint64_t kHilImuPeriod_us = 4000;

/// HIL_ACTUATOR_CONTROLS from the board's HIL instance outside lockstep (spec: "HIL_ACTUATOR_CONTROLS (200 Hz)").
inline constexpr double kActuatorStreamRate_hz = 200.0;
inline constexpr uint64_t kActuatorStreamPeriod_us = 5000;
static_assert(kActuatorStreamPeriod_us * kActuatorStreamRate_hz == 1e6, "the period is the rate's inverse");

/// HIL_ACTUATOR_CONTROLS.flags the VOXL2 sends for a quad (motors 0-3 as a bitmask), per the spec;
/// upstream PX4 sends 0.
inline constexpr uint64_t kVoxl2ActuatorFlags = 0x0F;

}  // namespace hitl
