// The physics step (world physics.step_s) against the sensors: HIL_SENSOR goes out after a step,
// so a step that does not divide the IMU, magnetometer and barometer periods would send them late
// and at the wrong rate (0.1 s: HIL_SENSOR at 10 Hz). Such a step is refused, saying why and which
// steps work. (GPS, 30 Hz, never divides: it runs on absolute due times, within one step.)
#pragma once

#include "base/common/expected.h"
#include "engine/model/vehicle_config.h"

namespace hitl::hil {

Status check_step_divides_sensor_periods(double step_s, const model::VehicleConfig& vehicle);

}  // namespace hitl::hil
