// Gazebo's MulticopterMotorModel for one rotor, as pure functions (world ENU quantities).
//   omega_ref = (u + input_offset) * input_scaling + zero_position_armed, clamped to max_rot_velocity
//   rotor speed: first-order lag to omega_ref, time constant up or down, discretised exactly:
//     omega <- omega_ref + (omega - omega_ref) exp(-dt / tau)
//   thrust   = kF omega^2 * clamp(1 - |v_axial| / axial_speed_falloff, 0, 1), along the rotor axis,
//              at the hub
//   drag     = -|omega| * rotor_drag_coefficient * v_perp, at the hub (v_perp: airspeed in the
//              rotor plane)
//   yaw drag torque on the frame = -turning * kM * kF omega^2 about the rotor axis (turning +1 CCW)
//   rolling moment on the frame = -|omega| * rolling_moment_coefficient * v_perp
// Gyroscopic coupling is not here: it comes from the rotor bodies in the multibody model.
#pragma once

#include <Eigen/Core>

#include "engine/model/vehicle_config.h"

namespace hitl::model {

/// +1 for CCW (spin about +z FLU), -1 for CW.
double spin_sign(Turning turning);

/// Speed reference [rad/s, >= 0] for a normalized command u (already clamped to 0..1).
double omega_reference_rad_s(const RotorConfig& rotor, double u, bool armed);

/// Rotor speed after dt following `omega_ref` from `omega` (both magnitudes, rad/s).
double next_rotor_speed_rad_s(const RotorConfig& rotor, double omega_rad_s, double omega_ref_rad_s, double dt_s);

struct RotorLoads {
  Eigen::Vector3d force_at_hub_ENU_N = Eigen::Vector3d::Zero();      ///< thrust + rotor drag
  Eigen::Vector3d torque_on_frame_ENU_Nm = Eigen::Vector3d::Zero();  ///< yaw drag torque + rolling moment
};

/// Loads of a rotor spinning at |omega| with axis `axis_ENU` (unit, the rotor's +z) whose hub moves
/// through the air at `v_air_ENU_m_s` (hub velocity minus wind).
RotorLoads rotor_loads(const RotorConfig& rotor, double omega_rad_s, const Eigen::Vector3d& axis_ENU,
                       const Eigen::Vector3d& v_air_ENU_m_s);

/// A degraded or failed motor (a fault, engine/faults): its thrust, drag and torques on the frame
/// x k (k = 0: out; the rotor still spins at the commanded speed but moves no air).
RotorLoads scaled_rotor_loads(const RotorLoads& loads, double k);

}  // namespace hitl::model
