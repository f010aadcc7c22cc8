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
#include "engine/sensors/geodesy.h"
#include "engine/sensors/gps.h"
#include "engine/sensors/imu.h"
#include "engine/sensors/magnetometer.h"
#include "engine/sensors/samples.h"
#include "engine/sensors/scheduler.h"
#include "engine/sensors/unit_set.h"

namespace hitl::sensors {

/// The samples taken after one step: only the sensors that were due; truth always.
struct SensorFrame {
  std::optional<ImuSample> imu;
  std::optional<MagSample> mag;
  std::optional<BaroSample> baro;
  std::optional<GpsSample> gps;
  UnitSamples units;  ///< the enabled units' samples that were due, with their faults
  GroundTruth truth;
};

class SensorSuite {
 public:
  SensorSuite(const model::VehicleConfig& vehicle, const model::WorldConfig& world, std::uint64_t seed,
              const UnitConfigs& units = {});
  /// Samples every sensor due at state.time_s; the units' with `unit_faults` applied (the built-in
  /// sensors' faults are applied after, by engine/faults' SensorFaults).
  SensorFrame sample_due(const model::VehicleState& state, const UnitFaults& unit_faults = {});
  /// Noise processes, biases and schedule back to their start (a reset run repeats).
  void reset();

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
};

}  // namespace hitl::sensors
