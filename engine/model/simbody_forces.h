// PRIVATE to engine/model (includes Simbody): the x500's applied forces as one Simbody custom
// force: gravity (as Simbody's Force::UniformGravity computes it), motor torques on the rotor pins, rotor thrust/drag at the hubs, yaw drag torque and
// rolling moment on the frame, linear body drag, an external force, and the ground contact
// (legs and frame points).
#pragma once

#include <array>

#include <Eigen/Core>
#include "engine/model/simbody_include.h"

#include "engine/model/ground_contact.h"
#include "engine/model/vehicle_config.h"

namespace hitl::model {

/// Inputs the forces read; written between steps by the owner (who then invalidates the cache at
/// Stage::Dynamics so that they act in the next step).
struct ForceInputs {
  std::array<double, 4> omega_ref_rad_s{};
  Eigen::Vector3d wind_ENU_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d external_force_ENU_N = Eigen::Vector3d::Zero();
  std::array<ContactAnchor, kContactPoints> anchors{};  ///< per contact_points() entry
  double substep_s = 0.004;  ///< the integrator's fixed step (the motor torque aims to land on the lag curve)
  std::array<double, 4> effectiveness{1.0, 1.0, 1.0, 1.0};  ///< per rotor, thrust and torque x k (a motor fault)
};

inline SimTK::Vec3 to_simtk(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d to_eigen(const SimTK::Vec3& v) { return {v[0], v[1], v[2]}; }

/// Each body's pose and velocity is read from Simbody once per evaluation and the forces are added
/// into the arrays directly (the arithmetic of MobilizedBody::applyForceToBodyPoint and
/// findStationVelocityInGround, without their per-call cache look-ups).
class MulticopterForces : public SimTK::Force::Custom::Implementation {
 public:
  /// Build after every body is in `matter` (the handles are kept); call set_rotor_u_indices() once
  /// the model is realised, before the first evaluation.
  MulticopterForces(const VehicleConfig& vehicle, double gravity_m_s2, const SimTK::SimbodyMatterSubsystem& matter,
                    SimTK::MobilizedBodyIndex base, const std::array<SimTK::MobilizedBodyIndex, 4>& rotors,
                    const ForceInputs& inputs);
  /// Where each rotor pin's generalized speed sits in the state's u (fixed once the model is realised).
  void set_rotor_u_indices(const std::array<SimTK::UIndex, 4>& u) { rotor_u_ = u; }

  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>& particle_forces, SimTK::Vector& mobility_forces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }

 private:
  void add_gravity(SimTK::MobilizedBodyIndex body, double mass_kg, const SimTK::Rotation& R_G_B,
                   SimTK::Vector_<SimTK::SpatialVec>& body_forces) const;

  VehicleConfig vehicle_;
  SimTK::Vec3 g_ENU_m_s2_;
  std::array<ContactPoint, kContactPoints> contacts_;
  const SimTK::MobilizedBody& base_;
  std::array<const SimTK::MobilizedBody*, 4> rotors_;
  std::array<SimTK::UIndex, 4> rotor_u_;
  const ForceInputs& inputs_;
};

}  // namespace hitl::model
