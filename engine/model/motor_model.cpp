#include "engine/model/motor_model.h"

#include <algorithm>
#include <cmath>

namespace hitl::model {

double spin_sign(Turning turning) { return turning == Turning::Ccw ? 1.0 : -1.0; }

double omega_reference_rad_s(const RotorConfig& rotor, double u, bool armed) {
  if (!armed) return 0.0;
  const double omega = (u + rotor.input_offset) * rotor.input_scaling_rad_s + rotor.zero_position_armed_rad_s;
  return std::clamp(omega, 0.0, rotor.max_rot_velocity_rad_s);
}

double next_rotor_speed_rad_s(const RotorConfig& rotor, double omega_rad_s, double omega_ref_rad_s, double dt_s) {
  const double tau_s = omega_ref_rad_s > omega_rad_s ? rotor.time_constant_up_s : rotor.time_constant_down_s;
  return omega_ref_rad_s + (omega_rad_s - omega_ref_rad_s) * std::exp(-dt_s / tau_s);
}

RotorLoads rotor_loads(const RotorConfig& rotor, double omega_rad_s, const Eigen::Vector3d& axis_ENU,
                       const Eigen::Vector3d& v_air_ENU_m_s) {
  const double w = std::abs(omega_rad_s);
  const double v_axial_m_s = v_air_ENU_m_s.dot(axis_ENU);
  const Eigen::Vector3d v_perp_ENU = v_air_ENU_m_s - v_axial_m_s * axis_ENU;
  const double thrust_N = rotor.motor_constant_N_s2 * w * w;
  const double falloff = std::clamp(1.0 - std::abs(v_axial_m_s) / rotor.axial_speed_falloff_m_s, 0.0, 1.0);
  RotorLoads loads;
  loads.force_at_hub_ENU_N = thrust_N * falloff * axis_ENU - w * rotor.rotor_drag_coefficient * v_perp_ENU;
  loads.torque_on_frame_ENU_Nm = -spin_sign(rotor.turning) * rotor.moment_constant_m * thrust_N * axis_ENU -
                                 w * rotor.rolling_moment_coefficient * v_perp_ENU;
  return loads;
}

RotorLoads scaled_rotor_loads(const RotorLoads& loads, double k) {
  return {loads.force_at_hub_ENU_N * k, loads.torque_on_frame_ENU_Nm * k};
}

}  // namespace hitl::model
