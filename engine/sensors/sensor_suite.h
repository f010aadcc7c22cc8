// All sensors of a vehicle with their schedule: what the session loop calls after each physics
// step. Each sensor has its own RNG stream derived from the seed. The IMU, magnetometer and
// barometer (one HIL_SENSOR) and the GPS (HIL_GPS) are built in; the sensor units (unit.h: the
// rangefinder, ...) come from their registration (units.h) and their settings.
#pragma once

#include <cstdint>
#include <optional>

#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/barometer.h"
#include "engine/sensors/data_path_timing.h"
#include "engine/sensors/geodesy.h"
#include "engine/sensors/gps.h"
#include "engine/sensors/imu.h"
#include "engine/sensors/magnetometer.h"
#include "engine/sensors/samples.h"
#include "engine/sensors/scheduler.h"
#include "engine/sensors/sensor_frame.h"
#include "engine/sensors/unit_set.h"

namespace hitl::sensors {

class SensorSuite {
 public:
  SensorSuite(const model::VehicleConfig& vehicle, const model::WorldConfig& world, std::uint64_t seed,
              const UnitConfigs& units = {});
  /// Samples every sensor due at state.time_s; the units' with `unit_faults` applied (the built-in
  /// sensors' faults are applied after, by engine/faults' SensorFaults).
  SensorFrame sample_due(const model::VehicleState& state, const UnitFaults& unit_faults = {});
  /// Noise processes, biases and schedule back to their start (a reset run repeats).
  void reset();
  /// From now on, deliver() delays the samples as the board's data path does.
  void set_data_path_timing(const DataPathTimingConfig& config, std::uint64_t seed) { data_path_.emplace(config, seed); }
  /// `frame` as the flight stack reads it at `now_s`: through the board's data path when one is
  /// set (after the sensor faults: they act at the sensor), else unchanged.
  void deliver(SensorFrame& frame, double now_s) {
    if (data_path_) data_path_->apply(frame, now_s);
  }
  const std::optional<DataPathTiming>& data_path_timing() const { return data_path_; }

  Imu& imu() { return imu_; }
  const Imu& imu() const { return imu_; }
  Magnetometer& magnetometer() { return mag_; }
  Barometer& barometer() { return baro_; }
  Gps& gps() { return gps_; }
  const LocalGeodesy& geodesy() const { return geodesy_; }
  const UnitSet& units() const { return units_; }

 private:
  Imu imu_;
  Magnetometer mag_;
  Barometer baro_;
  Gps gps_;
  LocalGeodesy geodesy_;
  SensorScheduler scheduler_;
  UnitSet units_;
  std::optional<DataPathTiming> data_path_;
};

}  // namespace hitl::sensors
