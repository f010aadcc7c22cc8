// The compiled-in defaults: the PX4 Gazebo x500 (x500.md) and PX4 SITL's default world.
// This is the one place their numbers live; config files are merged over these, and tests and
// docs refer to them through these functions.
#pragma once

#include "engine/model/vehicle_config.h"
#include "engine/model/world_config.h"

namespace hitl::model {

/// The x500 of PX4-gazebo-models (x500_base + x500), with Gazebo-classic-class sensor noise.
VehicleConfig x500_vehicle_config();

/// PX4 SITL's default home (Zurich), its magnetic field, ISA, no wind, 4 ms physics step.
WorldConfig default_world_config();

/// Normalized motor command that makes all four rotors of `vehicle` carry its weight under `world`
/// gravity (x500: about 0.769).
double hover_command(const VehicleConfig& vehicle, const WorldConfig& world);

}  // namespace hitl::model
