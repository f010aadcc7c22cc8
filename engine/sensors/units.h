// The registered sensor units (engine/sensors/unit.h): a unit's folder plus its line here is all
// that adding a sensor takes (docs/architecture.md "Adding things"). The order is the order of
// their flags, their faults in the catalogue, and their messages in a step's datagram.
#pragma once

#include "engine/sensors/rangefinder/rangefinder.h"
#include "engine/sensors/unit.h"

namespace hitl::sensors {

using SensorUnits = UnitList<Rangefinder>;

}  // namespace hitl::sensors
