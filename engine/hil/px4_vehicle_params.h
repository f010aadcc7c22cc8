// The parameters that make PX4 fly hitl's vehicle (docs/sim.md "Flying PX4 SITL"): the control
// allocation's geometry from the vehicle's rotors, and the hover thrust its mass and rotors give.
// PX4's SITL airframe 10016 (none_iris) is an Iris: without these it allocates for the wrong arms
// and hovers at the wrong thrust.
#pragma once

#include <vector>

#include "engine/model/vehicle_config.h"
#include "engine/px4/px4_process.h"

namespace hitl::hil {

/// PX4's yaw allocation ratio for each rotor, signed by its turning (PX4's x500 airframe's value;
/// the allocation's ratio, not the rotor's drag physics).
inline constexpr double kPx4RotorMomentRatio = 0.05;

/// CA_ROTOR_COUNT, CA_ROTORi_PX/PY (FRD, m) and CA_ROTORi_KM (+ counter-clockwise), MPC_THR_HOVER
/// (hover thrust over full thrust: PX4's normalised thrust with THR_MDL_FAC 1) and THR_MDL_FAC 1
/// (thrust grows with the square of the command, as the model's rotors). The x500: 0.174 m arms,
/// hover 0.59.
std::vector<px4::Px4Param> px4_vehicle_params(const model::VehicleConfig& vehicle, double gravity_m_s2);

}  // namespace hitl::hil
