#include "engine/model/simbody_forces.h"

#include <cmath>

#include "engine/model/motor_model.h"

namespace hitl::model {
namespace {

/// MobilizedBody::applyForceToBodyPoint with the body's rotation already at hand.
void apply_force_at_point(SimTK::MobilizedBodyIndex body, const SimTK::Rotation& R_G_B, const SimTK::Vec3& p_B,
                          const SimTK::Vec3& f_G, SimTK::Vector_<SimTK::SpatialVec>& body_forces) {
  body_forces[body] += SimTK::SpatialVec((R_G_B * p_B) % f_G, f_G);
}

}  // namespace

MulticopterForces::MulticopterForces(const VehicleConfig& vehicle, double gravity_m_s2,
                                     const SimTK::SimbodyMatterSubsystem& matter,
                                     SimTK::MobilizedBodyIndex base,
                                     const std::array<SimTK::MobilizedBodyIndex, 4>& rotors, const ForceInputs& inputs)
    : vehicle_(vehicle), g_ENU_m_s2_(0.0, 0.0, -gravity_m_s2), contacts_(contact_points(vehicle.landing_gear)), base_(matter.getMobilizedBody(base)), inputs_(inputs) {
  for (std::size_t i = 0; i < rotors.size(); ++i) rotors_[i] = &matter.getMobilizedBody(rotors[i]);
}

void MulticopterForces::add_gravity(SimTK::MobilizedBodyIndex body, double mass_kg, const SimTK::Rotation& R_G_B,
                                    SimTK::Vector_<SimTK::SpatialVec>& body_forces) const {
  const SimTK::Vec3 com_G = R_G_B * SimTK::Vec3(0);
  const SimTK::Vec3 f_G = mass_kg * g_ENU_m_s2_;
  body_forces[body] += SimTK::SpatialVec(com_G % f_G, f_G);
}

void MulticopterForces::calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                                  SimTK::Vector_<SimTK::Vec3>& /*particle_forces*/,
                                  SimTK::Vector& mobility_forces) const {
  const SimTK::MobilizedBodyIndex base_index = base_.getMobilizedBodyIndex();
  const SimTK::Transform& X_ENU_FLU = base_.getBodyTransform(state);
  const SimTK::SpatialVec& V_ENU_FLU = base_.getBodyVelocity(state);  // angular, linear (origin)
  const SimTK::Rotation& R_FLU_to_ENU = X_ENU_FLU.R();
  const SimTK::Vector& u = state.getU();
  const Eigen::Vector3d wind_ENU_m_s = inputs_.wind_ENU_m_s;
  const double h_s = inputs_.substep_s;

  // Gravity first, body by body in index order, with Force::UniformGravity's arithmetic (a force
  // at the mass centre, which is each body's origin here), so the sums come out as they did when
  // it was a separate Simbody force element.
  add_gravity(base_index, vehicle_.base.mass_kg, R_FLU_to_ENU, body_forces);
  std::array<const SimTK::Transform*, 4> X_ENU_R;
  for (std::size_t i = 0; i < rotors_.size(); ++i) {
    X_ENU_R[i] = &rotors_[i]->getBodyTransform(state);
    add_gravity(rotors_[i]->getMobilizedBodyIndex(), vehicle_.rotors[i].mass_kg, X_ENU_R[i]->R(), body_forces);
  }

  for (std::size_t i = 0; i < rotors_.size(); ++i) {
    const RotorConfig& rc = vehicle_.rotors[i];
    const SimTK::MobilizedBody& rotor = *rotors_[i];
    // Motor: a torque on the pin (its reaction acts on the frame) sized so that one integrator
    // step moves the spin rate onto the first-order lag curve towards the reference.
    const double s = spin_sign(rc.turning);
    const double omega_pin_rad_s = u[rotor_u_[i]];   // about +z, relative to frame
    const double omega_rad_s = s * omega_pin_rad_s;  // along the spin direction
    const double omega_next_rad_s = next_rotor_speed_rad_s(rc, omega_rad_s, inputs_.omega_ref_rad_s[i], h_s);
    const double torque_Nm = rc.inertia_kgm2.z() * s * (omega_next_rad_s - omega_rad_s) / h_s;
    mobility_forces[rotor_u_[i]] += torque_Nm;

    // Aerodynamics at the hub; axis = rotor +z (= frame +z) in ENU.
    const Eigen::Vector3d axis_ENU = to_eigen(X_ENU_R[i]->z());
    const Eigen::Vector3d v_hub_ENU_m_s = to_eigen(rotor.getBodyVelocity(state)[1]);
    const RotorLoads loads = scaled_rotor_loads(rotor_loads(rc, omega_pin_rad_s, axis_ENU, v_hub_ENU_m_s - wind_ENU_m_s),
                                                inputs_.effectiveness[i]);
    apply_force_at_point(rotor.getMobilizedBodyIndex(), X_ENU_R[i]->R(), SimTK::Vec3(0), to_simtk(loads.force_at_hub_ENU_N),
                         body_forces);
    body_forces[base_index][0] += to_simtk(loads.torque_on_frame_ENU_Nm);
  }

  // Linear body drag per body axis, and the external force, at the base origin.
  const SimTK::Vec3& w_ENU_rad_s = V_ENU_FLU[0];
  const SimTK::Vec3& v_ENU_m_s = V_ENU_FLU[1];
  const Eigen::Vector3d v_air_FLU_m_s = to_eigen(~R_FLU_to_ENU * (v_ENU_m_s - to_simtk(wind_ENU_m_s)));
  const Eigen::Vector3d drag_FLU_N = -vehicle_.base.linear_drag_N_s_m.cwiseProduct(v_air_FLU_m_s);
  const SimTK::Vec3 f_base_ENU_N = R_FLU_to_ENU * to_simtk(drag_FLU_N) + to_simtk(inputs_.external_force_ENU_N);
  apply_force_at_point(base_index, R_FLU_to_ENU, SimTK::Vec3(0), f_base_ENU_N, body_forces);

  // Ground contact: legs and frame points (station velocity as MobilizedBody::findStationVelocityInGround).
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const SimTK::Vec3 p_FLU_m = to_simtk(contacts_[k].p_FLU_m);
    const Eigen::Vector3d p_ENU_m = to_eigen(X_ENU_FLU * p_FLU_m);
    if (p_ENU_m.z() >= 0.0) continue;
    const Eigen::Vector3d v_point_ENU_m_s = to_eigen(v_ENU_m_s + w_ENU_rad_s % (R_FLU_to_ENU * p_FLU_m));
    const Eigen::Vector3d f_ENU_N =
        ground_contact_force_ENU_N(vehicle_.landing_gear, contacts_[k], p_ENU_m, v_point_ENU_m_s, inputs_.anchors[k]);
    apply_force_at_point(base_index, R_FLU_to_ENU, p_FLU_m, to_simtk(f_ENU_N), body_forces);
  }
}

}  // namespace hitl::model
