#include "engine/model/multicopter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "engine/model/simbody_include.h"

#include "engine/model/config_json.h"
#include "engine/model/motor_model.h"
#include "engine/model/simbody_forces.h"
#include "engine/model/wind.h"

namespace hitl::model {
namespace {

SimTK::Inertia inertia_of(const Eigen::Vector3d& i_kgm2) { return {i_kgm2.x(), i_kgm2.y(), i_kgm2.z()}; }

std::string format_vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

bool all_finite(const SimTK::Vector& v) {
  for (int i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace

struct Multicopter::Impl {
  Impl(const VehicleConfig& vehicle_config, const WorldConfig& world_config, std::uint64_t seed)
      : vehicle(vehicle_config),
        world(world_config),
        matter(system),
        forces(system),
        wind(world_config.wind, seed) {
    substeps = std::max(1, static_cast<int>(std::ceil(world.physics.step_s / world.physics.max_substep_s - 1e-9)));
    inputs.substep_s = world.physics.step_s / substeps;
    contacts = contact_points(vehicle.landing_gear);

    SimTK::Body::Rigid base_body(SimTK::MassProperties(vehicle.base.mass_kg, SimTK::Vec3(0), inertia_of(vehicle.base.inertia_kgm2)));
    SimTK::MobilizedBody::Free base(matter.Ground(), SimTK::Transform(), base_body, SimTK::Transform());
    base_index = base.getMobilizedBodyIndex();
    for (std::size_t i = 0; i < rotor_index.size(); ++i) {
      const RotorConfig& rc = vehicle.rotors[i];
      SimTK::Body::Rigid rotor_body(SimTK::MassProperties(rc.mass_kg, SimTK::Vec3(0), inertia_of(rc.inertia_kgm2)));
      // Pin about z of both frames: the rotor spins about body z at its hub.
      SimTK::MobilizedBody::Pin rotor(base, SimTK::Transform(to_simtk(rc.position_FLU_m)), rotor_body, SimTK::Transform());
      rotor_index[i] = rotor.getMobilizedBodyIndex();
    }
    force_elements = new MulticopterForces(vehicle, world.gravity_m_s2, matter, base_index, rotor_index, inputs);
    SimTK::Force::Custom(forces, force_elements);  // the force subsystem owns force_elements
    system.realizeTopology();
    std::array<SimTK::UIndex, 4> rotor_u;
    for (std::size_t i = 0; i < rotor_index.size(); ++i) {
      rotor_u[i] = matter.getMobilizedBody(rotor_index[i]).getFirstUIndex(system.getDefaultState());
    }
    force_elements->set_rotor_u_indices(rotor_u);
    rotor_u_index = rotor_u;

    integrator.emplace(system, inputs.substep_s);
    integrator->setAllowInterpolation(false);
    integrator->setReturnEveryInternalStep(false);
  }

  /// The base's pose and velocity in one read of a state realised through Velocity, shared by the
  /// IMU means, the blow-up check, the published state and the contact anchors.
  struct BaseKinematics {
    SimTK::Transform X_ENU_FLU;
    SimTK::SpatialVec V_ENU;  ///< angular (rad/s), linear velocity of the origin (m/s), both ENU
  };
  BaseKinematics base_kinematics() const {
    system.realize(state, SimTK::Stage::Velocity);
    return {base().getBodyTransform(state), base().getBodyVelocity(state)};
  }

  const SimTK::MobilizedBody& base() const { return matter.getMobilizedBody(base_index); }

  void reset(const InitialCondition& initial) {
    SimTK::State s = system.getDefaultState();
    const Eigen::Quaterniond q = initial.q_FLU_to_ENU.normalized();
    const SimTK::Rotation R_FLU_to_ENU(SimTK::Quaternion(q.w(), q.x(), q.y(), q.z()));
    base().setQToFitTransform(s, SimTK::Transform(R_FLU_to_ENU, to_simtk(initial.p_ENU_m)));
    base().setUToFitVelocity(s, SimTK::SpatialVec(R_FLU_to_ENU * to_simtk(initial.w_FLU_rad_s), to_simtk(initial.v_ENU_m_s)));
    for (std::size_t i = 0; i < rotor_index.size(); ++i) {
      matter.getMobilizedBody(rotor_index[i])
          .setOneU(s, SimTK::MobilizerUIndex(0), spin_sign(vehicle.rotors[i].turning) * initial.rotor_speed_rad_s[i]);
    }
    inputs.omega_ref_rad_s.fill(0.0);
    inputs.anchors = {};
    wind.reset();
    inputs.wind_ENU_m_s = wind.velocity_ENU_m_s();
    // The integrator projects and realises the initial state; the steps are then taken here
    // (semi_explicit_euler_substep) on a copy of it.
    integrator->initialize(s);
    state = integrator->getState();
    quaternion_tolerance = integrator->getConstraintToleranceInUse();
    base_quaternion_q = base().getFirstQIndex(state);  // a Free mobilizer's q: quaternion, then position
    qdot.resize(state.getNQ());
    next_q.resize(state.getNQ());
    next_u.resize(state.getNU());
    failure.reset();
    step_count = 0;
    const BaseKinematics k = base_kinematics();
    published = extract(k, nullptr, nullptr);
    update_anchors(k);
  }

  /// One sub-step of Simbody's SemiExplicitEulerIntegrator to t1_s, the same arithmetic in the same
  /// order (u1 = u0 + h udot0; q1 = q0 + h N(q0) u1; quaternions projected as the integrator does),
  /// without what only serves features this model does not use: the integrator's copies of the
  /// state, its second Position realisation (old q at the new time, for prescribed motion), velocity
  /// projection (no constraints), events and interpolation. Leaves the state realised through
  /// Velocity; forces and accelerations are computed at the start of the next sub-step, with the
  /// inputs of that step.
  void semi_explicit_euler_substep(double t1_s) {
    system.realize(state, SimTK::Stage::Acceleration);
    const double h_s = t1_s - state.getTime();
    // Element by element, the same operations as Simbody's u0 + h * udot0 without its temporaries.
    const SimTK::Vector& u0 = state.getU();
    const SimTK::Vector& udot0 = state.getUDot();
    for (int i = 0; i < u0.size(); ++i) next_u[i] = u0[i] + h_s * udot0[i];
    system.multiplyByN(state, next_u, qdot);  // N(q0) u1, q0 still realised
    const SimTK::Vector& q0 = state.getQ();
    for (int i = 0; i < q0.size(); ++i) next_q[i] = q0[i] + h_s * qdot[i];
    project_quaternion(next_q);
    state.updQ() = next_q;  // each upd* invalidates its stage and above
    state.updU() = next_u;
    state.updTime() = t1_s;
    system.realize(state, SimTK::Stage::Velocity);
  }

  /// The integrator's position projection for this model, whose only position constraint is the
  /// base's unit quaternion (SimbodyMatterSubsystemRep::projectQ in Simbody 3.7 with no holonomic
  /// constraints): when the quaternion's length error |‖quat‖ − 1| (its RMS over one element)
  /// exceeds the constraint tolerance, quat ← quat / ‖quat‖. Done on q before it goes into the
  /// state, so Position is realised once, at the final q.
  void project_quaternion(SimTK::Vector& q) const {
    SimTK::Vec4 quat(q[base_quaternion_q], q[base_quaternion_q + 1], q[base_quaternion_q + 2], q[base_quaternion_q + 3]);
    const SimTK::Real length_error = quat.norm() - SimTK::Real(1);
    SimTK::Real sum_squares = 0;
    sum_squares += SimTK::square(length_error);
    if (!(std::sqrt(sum_squares / 1) > quaternion_tolerance)) return;  // NaN: left to the blow-up check
    quat = quat / quat.norm();
    for (int i = 0; i < 4; ++i) q[base_quaternion_q + i] = quat[i];
  }

  /// Sums over one step's sub-steps: the specific force (each sub-step in its own body frame) and
  /// the body rate, whose means the IMU reads.
  struct StepMeans {
    Eigen::Vector3d specific_force_FLU_m_s2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d w_FLU_rad_s = Eigen::Vector3d::Zero();
  };

  /// The public state from the current state's base kinematics `k`; `previous` gives the velocities
  /// one step back (for the accelerations) and `means` the step's averages; none at reset (at rest
  /// by definition).
  VehicleState extract(const BaseKinematics& k, const VehicleState* previous, const StepMeans* means) const {
    const SimTK::Transform& X_ENU_FLU = k.X_ENU_FLU;
    const SimTK::Quaternion q = X_ENU_FLU.R().convertRotationToQuaternion();
    VehicleState out;
    out.time_s = state.getTime();
    out.step = step_count;
    out.p_ENU_m = to_eigen(X_ENU_FLU.p());
    out.q_FLU_to_ENU = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    out.v_ENU_m_s = to_eigen(k.V_ENU[1]);
    out.w_FLU_rad_s = to_eigen(~X_ENU_FLU.R() * k.V_ENU[0]);
    if (previous) {
      const double dt_s = world.physics.step_s;
      out.a_ENU_m_s2 = (out.v_ENU_m_s - previous->v_ENU_m_s) / dt_s;
      out.alpha_FLU_rad_s2 = (out.w_FLU_rad_s - previous->w_FLU_rad_s) / dt_s;
    }
    const Eigen::Vector3d g_ENU_m_s2(0.0, 0.0, -world.gravity_m_s2);
    if (means) {
      out.specific_force_FLU_m_s2 = means->specific_force_FLU_m_s2;
      out.w_step_mean_FLU_rad_s = means->w_FLU_rad_s;
    } else {
      out.specific_force_FLU_m_s2 = out.q_FLU_to_ENU.conjugate() * (out.a_ENU_m_s2 - g_ENU_m_s2);
      out.w_step_mean_FLU_rad_s = out.w_FLU_rad_s;
    }
    const SimTK::Vector& u = state.getU();
    for (std::size_t i = 0; i < rotor_u_index.size(); ++i) out.rotor_speed_rad_s[i] = std::abs(u[rotor_u_index[i]]);
    out.wind_ENU_m_s = inputs.wind_ENU_m_s;
    out.ground_clearance_m = std::numeric_limits<double>::infinity();
    for (const ContactPoint& c : contacts) {
      out.ground_clearance_m = std::min(out.ground_clearance_m, (out.p_ENU_m + out.q_FLU_to_ENU * c.p_FLU_m).z());
    }
    out.on_ground = out.ground_clearance_m < 0.0;
    return out;
  }

  void update_anchors(const BaseKinematics& base_k) {
    const SimTK::Transform& X_ENU_FLU = base_k.X_ENU_FLU;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const SimTK::Vec3 p_FLU_m = to_simtk(contacts[k].p_FLU_m);
      // MobilizedBody::findStationVelocityInGround's arithmetic.
      const SimTK::Vec3 v_ENU_m_s = base_k.V_ENU[1] + base_k.V_ENU[0] % (X_ENU_FLU.R() * p_FLU_m);
      update_contact_anchor(vehicle.landing_gear, contacts[k], to_eigen(X_ENU_FLU * p_FLU_m), to_eigen(v_ENU_m_s),
                            inputs.anchors[k]);
    }
  }

  /// Why the current state is not acceptable, if it is not (`k`: its base kinematics, if finite).
  std::optional<std::string> blow_up_reason(const BaseKinematics& k) const {
    if (!all_finite(state.getQ()) || !all_finite(state.getU())) return std::string("state is not finite");
    const double speed_m_s = k.V_ENU[1].norm();
    const double rate_rad_s = k.V_ENU[0].norm();
    if (speed_m_s <= world.physics.max_speed_m_s && rate_rad_s <= world.physics.max_angular_rate_rad_s) {
      return std::nullopt;  // the usual case: no stream built
    }
    std::ostringstream why;
    if (!(speed_m_s <= world.physics.max_speed_m_s)) {
      why << "speed " << speed_m_s << " m/s exceeds physics.max_speed_m_s " << world.physics.max_speed_m_s;
    } else {
      why << "angular rate " << rate_rad_s << " rad/s exceeds physics.max_angular_rate_rad_s "
          << world.physics.max_angular_rate_rad_s;
    }
    return why.str();
  }

  Status step() {
    if (failure) return *failure;
    const double dt_s = world.physics.step_s;
    inputs.wind_ENU_m_s = wind.advance(dt_s);
    // Inputs changed since the state was last realized: forces must be recomputed in this step.
    state.invalidateAllCacheAtOrAbove(SimTK::Stage::Dynamics);
    const std::uint64_t next = step_count + 1;
    std::optional<std::string> reason;
    StepMeans means;
    BaseKinematics k;
    try {
      // One sub-step at a time, summing what the IMU averages over the step.
      const double h_s = dt_s / substeps;
      const Eigen::Vector3d g_ENU_m_s2(0.0, 0.0, -world.gravity_m_s2);
      Eigen::Vector3d v_before_ENU_m_s = published.v_ENU_m_s;
      for (int i = 1; i <= substeps; ++i) {
        const double t_s = i == substeps ? static_cast<double>(next) * dt_s
                                         : static_cast<double>(step_count) * dt_s + i * h_s;
        semi_explicit_euler_substep(t_s);
        k = base_kinematics();
        const SimTK::Rotation& R_FLU_to_ENU = k.X_ENU_FLU.R();
        const Eigen::Vector3d v_ENU_m_s = to_eigen(k.V_ENU[1]);
        const Eigen::Vector3d a_ENU_m_s2 = (v_ENU_m_s - v_before_ENU_m_s) / h_s;
        means.specific_force_FLU_m_s2 += to_eigen(~R_FLU_to_ENU * to_simtk(a_ENU_m_s2 - g_ENU_m_s2));
        means.w_FLU_rad_s += to_eigen(~R_FLU_to_ENU * k.V_ENU[0]);
        v_before_ENU_m_s = v_ENU_m_s;
      }
      means.specific_force_FLU_m_s2 /= substeps;
      means.w_FLU_rad_s /= substeps;
      reason = blow_up_reason(k);
    } catch (const std::exception& e) {
      reason = std::string("Simbody: ") + e.what();
    }
    if (reason) {
      std::ostringstream msg;
      const VehicleState& g = published;
      msg << "physics blew up in step " << next << " (t = " << static_cast<double>(next) * dt_s << " s): " << *reason
          << "; last good state at t = " << g.time_s << " s: p_ENU_m " << format_vec(g.p_ENU_m) << ", v_ENU_m_s "
          << format_vec(g.v_ENU_m_s) << ", w_FLU_rad_s " << format_vec(g.w_FLU_rad_s) << ", rotor speeds ("
          << g.rotor_speed_rad_s[0] << ", " << g.rotor_speed_rad_s[1] << ", " << g.rotor_speed_rad_s[2] << ", "
          << g.rotor_speed_rad_s[3] << ") rad/s";
      failure = Error::failed(msg.str());
      return *failure;
    }
    step_count = next;
    published = extract(k, &published, &means);
    update_anchors(k);
    return Ok{};
  }

  VehicleConfig vehicle;
  WorldConfig world;
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter;
  SimTK::GeneralForceSubsystem forces;
  SimTK::MobilizedBodyIndex base_index;
  std::array<SimTK::MobilizedBodyIndex, 4> rotor_index;
  ForceInputs inputs;
  Wind wind;
  MulticopterForces* force_elements = nullptr;  ///< owned by `forces`
  std::array<SimTK::UIndex, 4> rotor_u_index;   ///< each rotor pin's speed in the state's u
  std::optional<SimTK::SemiExplicitEulerIntegrator> integrator;  ///< initialises the state on reset
  SimTK::State state;                    ///< the state stepped by semi_explicit_euler_substep()
  double quaternion_tolerance = 0.0;     ///< the integrator's constraint tolerance
  int base_quaternion_q = 0;             ///< where the base's quaternion starts in q
  SimTK::Vector qdot, next_q, next_u;    ///< scratch for a sub-step: N(q0) u1, q1, u1
  int substeps = 1;
  std::array<ContactPoint, kContactPoints> contacts;
  InputCounters counters;
  VehicleState published;
  std::uint64_t step_count = 0;
  std::optional<Error> failure;
};

Expected<std::unique_ptr<Multicopter>> Multicopter::create(const VehicleConfig& vehicle, const WorldConfig& world,
                                                           std::uint64_t seed) {
  if (Status s = validate(vehicle); !s) return s.error();
  if (Status s = validate(world); !s) return s.error();
  auto impl = std::make_unique<Impl>(vehicle, world, seed);
  std::unique_ptr<Multicopter> m(new Multicopter(std::move(impl)));
  m->reset();
  return m;
}

Multicopter::Multicopter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Multicopter::~Multicopter() = default;

CheckedCommand check_motor_command(double u) {
  if (!std::isfinite(u)) return {0.0, CommandFix::NonFinite};
  if (u < 0.0 || u > 1.0) return {std::clamp(u, 0.0, 1.0), CommandFix::OutOfRange};
  return {u, CommandFix::None};
}

void Multicopter::set_motor_commands(const MotorCommands& commands) {
  Impl& m = *impl_;
  for (std::size_t i = 0; i < commands.u.size(); ++i) {
    const auto checked = check_motor_command(commands.u[i]);
    if (checked.fix == CommandFix::NonFinite) ++m.counters.non_finite;
    if (checked.fix == CommandFix::OutOfRange) ++m.counters.out_of_range;
    m.inputs.omega_ref_rad_s[i] = omega_reference_rad_s(m.vehicle.rotors[i], checked.u, commands.armed);
  }
}

void Multicopter::set_motor_effectiveness(std::size_t i, double k) {
  if (i < impl_->inputs.effectiveness.size()) impl_->inputs.effectiveness[i] = std::isfinite(k) && k > 0.0 ? k : 0.0;
}

void Multicopter::set_wind_event(const Eigen::Vector3d& extra_ENU_m_s, double turbulence_sigma_m_s, double turbulence_tau_s) {
  impl_->wind.set_event(extra_ENU_m_s, turbulence_sigma_m_s, turbulence_tau_s);
}

void Multicopter::set_external_force_ENU_N(const Eigen::Vector3d& f_ENU_N) {
  impl_->inputs.external_force_ENU_N = f_ENU_N.allFinite() ? f_ENU_N : Eigen::Vector3d::Zero();
}

Status Multicopter::step() { return impl_->step(); }
void Multicopter::reset() { impl_->reset(resting_on_ground()); }
void Multicopter::reset(const InitialCondition& initial) { impl_->reset(initial); }
const VehicleState& Multicopter::state() const { return impl_->published; }
const InputCounters& Multicopter::input_counters() const { return impl_->counters; }
const VehicleConfig& Multicopter::vehicle_config() const { return impl_->vehicle; }
const WorldConfig& Multicopter::world_config() const { return impl_->world; }

InitialCondition Multicopter::resting_on_ground() const {
  const LandingGearConfig& gear = impl_->vehicle.landing_gear;
  double lowest_m = 0.0;
  for (const Eigen::Vector3d& p : gear.contact_points_FLU_m) lowest_m = std::min(lowest_m, p.z());
  // Sunk into the springs by the static load, shared by the four contact points.
  const double sink_m = total_mass_kg(impl_->vehicle) * impl_->world.gravity_m_s2 /
                        (static_cast<double>(gear.contact_points_FLU_m.size()) * gear.stiffness_N_m);
  InitialCondition rest;
  rest.p_ENU_m = {0.0, 0.0, -lowest_m - sink_m};
  return rest;
}

}  // namespace hitl::model
