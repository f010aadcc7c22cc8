#include "engine/hil/step_check.h"

#include <cmath>
#include <cstdio>

namespace hitl::hil {

Status check_step_divides_sensor_periods(double step_s, const model::VehicleConfig& vehicle) {
  const struct {
    const char* name;
    double rate_hz;
  } sensors[] = {{"IMU", vehicle.sensors.imu.rate_hz}, {"magnetometer", vehicle.sensors.mag.rate_hz},
                 {"barometer", vehicle.sensors.baro.rate_hz}};
  for (const auto& s : sensors) {
    if (!(s.rate_hz > 0)) continue;
    const double period_s = 1.0 / s.rate_hz;
    const double steps = period_s / step_s;
    if (std::fabs(steps - std::round(steps)) <= 1e-6 * steps && std::round(steps) >= 1) continue;
    char text[320];
    std::snprintf(text, sizeof text,
                  "physics.step_s %g does not divide the %s period %g s (%g Hz): its samples would go out late and at "
                  "the wrong rate. Use a step that does, e.g. %g, %g or %g",
                  step_s, s.name, period_s, s.rate_hz, 1.0 / vehicle.sensors.imu.rate_hz, 0.5 / vehicle.sensors.imu.rate_hz,
                  0.25 / vehicle.sensors.imu.rate_hz);
    return Error::input(text);
  }
  return Ok{};
}

}  // namespace hitl::hil
