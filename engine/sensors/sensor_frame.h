// What the sensors give after one physics step: the samples that were due, and the truth.
#pragma once

#include <optional>

#include "engine/sensors/samples.h"
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

}  // namespace hitl::sensors
