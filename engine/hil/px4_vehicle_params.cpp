#include "engine/hil/px4_vehicle_params.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace hitl::hil {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

}  // namespace

std::vector<px4::Px4Param> px4_vehicle_params(const model::VehicleConfig& vehicle, double gravity_m_s2) {
  std::vector<px4::Px4Param> out;
  out.push_back({"CA_ROTOR_COUNT", std::to_string(vehicle.rotors.size())});
  double full_thrust_N = 0;
  for (std::size_t i = 0; i < vehicle.rotors.size(); ++i) {
    const auto& r = vehicle.rotors[i];
    const std::string prefix = "CA_ROTOR" + std::to_string(i) + "_";
    out.push_back({prefix + "PX", number(r.position_FLU_m.x())});   // forward: FLU x = FRD x
    out.push_back({prefix + "PY", number(-r.position_FLU_m.y())});  // right: FRD y = -FLU y
    out.push_back({prefix + "KM", number(r.turning == model::Turning::Ccw ? kPx4RotorMomentRatio : -kPx4RotorMomentRatio)});
    // Full command: omega = (1 + offset) * scaling + zero, clamped to the rotor's maximum.
    const double omega_max_rad_s = std::min(r.max_rot_velocity_rad_s,
                                            (1.0 + r.input_offset) * r.input_scaling_rad_s + r.zero_position_armed_rad_s);
    full_thrust_N += r.motor_constant_N_s2 * omega_max_rad_s * omega_max_rad_s;
  }
  if (full_thrust_N > 0) {
    const double hover = model::total_mass_kg(vehicle) * gravity_m_s2 / full_thrust_N;
    out.push_back({"MPC_THR_HOVER", number(std::clamp(hover, 0.1, 0.8))});  // PX4's range for it
  }
  out.push_back({"THR_MDL_FAC", "1"});
  return out;
}

}  // namespace hitl::hil
