// Ground truth in MAVLink frames (NED/FRD) from the engine's state: for ODOMETRY (position NED,
// q FRD->NED, velocities and rates in the child frame FRD) and for truth-vs-estimate displays.
#pragma once

#include "engine/model/vehicle_state.h"
#include "engine/sensors/geodesy.h"
#include "engine/sensors/samples.h"

namespace hitl::sensors {

GroundTruth ground_truth(const model::VehicleState& state, const LocalGeodesy& geodesy);

}  // namespace hitl::sensors
