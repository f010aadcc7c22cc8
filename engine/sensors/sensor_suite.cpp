#include "engine/sensors/sensor_suite.h"

#include "engine/sensors/ground_truth.h"

namespace hitl::sensors {

SensorSuite::SensorSuite(const model::VehicleConfig& vehicle, const model::WorldConfig& world, std::uint64_t seed,
                         const UnitConfigs& units)
    : imu_(vehicle.sensors.imu, world, seed),
      mag_(vehicle.sensors.mag, world.magnetic_field, seed),
      baro_(vehicle.sensors.baro, world, seed),
      gps_(vehicle.sensors.gps, world.home, seed),
      geodesy_(world.home),
      scheduler_(vehicle.sensors.imu.rate_hz, vehicle.sensors.mag.rate_hz, vehicle.sensors.baro.rate_hz,
                 vehicle.sensors.gps.rate_hz),
      units_(units, world, seed, 1.0 / vehicle.sensors.imu.rate_hz) {}

SensorFrame SensorSuite::sample_due(const model::VehicleState& state, const UnitFaults& unit_faults) {
  const double t_s = state.time_s;
  const DueSensors due = scheduler_.due(t_s);
  SensorFrame frame;
  if (due.imu) frame.imu = imu_.sample(state, t_s);
  if (due.mag) frame.mag = mag_.sample(state, t_s);
  if (due.baro) frame.baro = baro_.sample(state, t_s);
  if (due.gps) frame.gps = gps_.sample(state, t_s);
  frame.units = units_.sample_due(state, unit_faults);
  frame.truth = ground_truth(state, geodesy_);
  return frame;
}

void SensorSuite::reset() {
  imu_.reset();
  mag_.reset();
  baro_.reset();
  gps_.reset();
  scheduler_.reset();
  units_.reset();
  if (data_path_) data_path_->reset();
}

}  // namespace hitl::sensors
