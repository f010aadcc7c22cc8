// The Simbody x500 through its public API: rest, free fall, hover, differential thrust, landing,
// friction, determinism, bad inputs and blow-up detection.
#include "engine/model/multicopter.h"

#include <cmath>

#include <gtest/gtest.h>

#include "engine/frames/frames.h"
#include "engine/model/x500_defaults.h"

namespace hitl::model {
namespace {

std::unique_ptr<Multicopter> make(const VehicleConfig& vehicle = x500_vehicle_config(),
                                  const WorldConfig& world = default_world_config(), std::uint64_t seed = 1) {
  auto created = Multicopter::create(vehicle, world, seed);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : created.error().message);
  return std::move(created.value());
}

void run_s(Multicopter& m, double seconds) {
  const auto steps = static_cast<int>(std::lround(seconds / m.world_config().physics.step_s));
  for (int i = 0; i < steps; ++i) ASSERT_TRUE(m.step().ok()) << m.step().error().message;
}

MotorCommands all_motors(double u) { return {{u, u, u, u}, true}; }

/// Airborne at `altitude_m` (base origin, ENU z), level, rotors already at hover speed and commanded to hover.
void start_hovering(Multicopter& m, double altitude_m) {
  const double u_h = hover_command(m.vehicle_config(), m.world_config());
  InitialCondition ic;
  ic.p_ENU_m = {0.0, 0.0, altitude_m};
  ic.rotor_speed_rad_s.fill(u_h * m.vehicle_config().rotors[0].input_scaling_rad_s);
  m.reset(ic);
  m.set_motor_commands(all_motors(u_h));
}

TEST(Multicopter, HoverCommandMatchesX500Table) {
  // x500.md: total mass 2.0643 kg, omega_h ~ 769.4 rad/s, u_h ~ 0.769.
  EXPECT_NEAR(total_mass_kg(x500_vehicle_config()), 2.0643, 1e-4);
  EXPECT_NEAR(hover_command(x500_vehicle_config(), default_world_config()), 0.7694, 1e-3);
}

TEST(Multicopter, RestsOnGroundWithoutDriftAndReadsOneG) {
  auto m = make();
  const VehicleState start = m->state();
  EXPECT_TRUE(start.on_ground);
  for (int i = 0; i < 2500; ++i) {  // 10 s
    ASSERT_TRUE(m->step().ok());
    ASSERT_NEAR(m->state().p_ENU_m.z(), start.p_ENU_m.z(), 1e-3) << "at step " << i;
  }
  const VehicleState& s = m->state();
  EXPECT_NEAR(s.time_s, 10.0, 1e-9);
  EXPECT_LT((s.p_ENU_m - start.p_ENU_m).head<2>().norm(), 1e-4);
  const Eigen::Vector3d f_FRD = frames::flu_to_frd(s.specific_force_FLU_m_s2);
  EXPECT_NEAR(f_FRD.x(), 0.0, 1e-6);
  EXPECT_NEAR(f_FRD.y(), 0.0, 1e-6);
  EXPECT_NEAR(f_FRD.z(), -9.80665, 1e-6);
}

TEST(Multicopter, FreeFallReachesGroundAtAnalyticTime) {
  auto m = make();
  const double drop_m = 10.0;
  InitialCondition ic = m->resting_on_ground();
  const double skid_height_m = -x500_vehicle_config().landing_gear.contact_points_FLU_m[0].z();
  ic.p_ENU_m.z() = drop_m + skid_height_m;  // skid bottoms 10 m above the ground
  m->reset(ic);
  double t_contact_s = -1.0;
  for (int i = 0; i < 1000 && t_contact_s < 0; ++i) {
    ASSERT_TRUE(m->step().ok());
    if (m->state().on_ground) t_contact_s = m->state().time_s;
  }
  const double t_analytic_s = std::sqrt(2.0 * drop_m / 9.80665);
  EXPECT_NEAR(t_contact_s, t_analytic_s, 0.02 * t_analytic_s);
  // Falling, the accelerometer reads (almost) nothing.
  EXPECT_LT(m->state().specific_force_FLU_m_s2.norm(), 1.0);
}

TEST(Multicopter, HoverCommandHoldsAltitude) {
  auto m = make();
  start_hovering(*m, 5.0);
  run_s(*m, 0.5);  // transient
  double z_min = 1e9, z_max = -1e9;
  for (int i = 0; i < 1250; ++i) {  // 5 s
    ASSERT_TRUE(m->step().ok());
    z_min = std::min(z_min, m->state().p_ENU_m.z());
    z_max = std::max(z_max, m->state().p_ENU_m.z());
  }
  EXPECT_LT(z_max - z_min, 0.1);
  EXPECT_NEAR(z_min, 5.0, 0.1);
  for (double w : m->state().rotor_speed_rad_s) EXPECT_NEAR(w, 769.4, 1.0);
}

TEST(Multicopter, MoreThanHoverLiftsLessSinks) {
  const double u_h = hover_command(x500_vehicle_config(), default_world_config());
  auto up = make();
  start_hovering(*up, 5.0);
  up->set_motor_commands(all_motors(u_h + 0.05));
  run_s(*up, 2.0);
  EXPECT_GT(up->state().p_ENU_m.z(), 5.5);
  EXPECT_GT(up->state().v_ENU_m_s.z(), 0.5);

  auto down = make();
  start_hovering(*down, 5.0);
  down->set_motor_commands(all_motors(u_h - 0.05));
  run_s(*down, 2.0);
  EXPECT_LT(down->state().p_ENU_m.z(), 4.5);
  EXPECT_LT(down->state().v_ENU_m_s.z(), -0.5);
}

TEST(Multicopter, TakesOffFromTheGround) {
  auto m = make();
  m->set_motor_commands(all_motors(0.85));
  run_s(*m, 2.0);
  EXPECT_FALSE(m->state().on_ground);
  EXPECT_GT(m->state().p_ENU_m.z(), 1.0);
  EXPECT_LT((m->state().p_ENU_m.head<2>()).norm(), 0.05);  // straight up
}

/// Body rates (FRD) after 0.2 s of hover with `delta` added to the given motors.
Eigen::Vector3d rates_FRD_after(const std::array<double, 4>& delta) {
  auto m = make();
  start_hovering(*m, 5.0);
  const double u_h = hover_command(m->vehicle_config(), m->world_config());
  MotorCommands c = all_motors(u_h);
  for (std::size_t i = 0; i < 4; ++i) c.u[i] += delta[i];
  m->set_motor_commands(c);
  run_s(*m, 0.2);
  return frames::flu_to_frd(m->state().w_FLU_rad_s);
}

TEST(Multicopter, FrontMotorsFasterPitchNoseUp) {
  const Eigen::Vector3d w = rates_FRD_after({0.05, 0.0, 0.05, 0.0});  // 0 front-right, 2 front-left
  EXPECT_GT(w.y(), 0.2);  // nose-up pitch rate is +y FRD
  EXPECT_LT(std::abs(w.x()), 0.05 * w.y());
  EXPECT_LT(std::abs(w.z()), 0.2 * w.y());
}

TEST(Multicopter, LeftMotorsFasterRollRight) {
  const Eigen::Vector3d w = rates_FRD_after({0.0, 0.05, 0.05, 0.0});  // 1 back-left, 2 front-left
  EXPECT_GT(w.x(), 0.2);  // right wing down is +x FRD
  EXPECT_LT(std::abs(w.y()), 0.05 * w.x());
}

TEST(Multicopter, CcwPairFasterYawsRight) {
  // CCW rotors (0, 1) push the frame clockwise seen from above: heading increases, +z FRD.
  const Eigen::Vector3d w = rates_FRD_after({0.05, 0.05, 0.0, 0.0});
  EXPECT_GT(w.z(), 0.05);
  EXPECT_LT(std::abs(w.x()) + std::abs(w.y()), 0.2 * w.z());
}

/// Drops the vehicle onto the ground at `touchdown_m_s`; returns how far it rebounded above its rest
/// height after the first touch [m], and leaves it 3 s later.
double land(Multicopter& m, double touchdown_m_s) {
  InitialCondition ic = m.resting_on_ground();
  const double z_rest = ic.p_ENU_m.z();
  ic.p_ENU_m.z() = -m.vehicle_config().landing_gear.contact_points_FLU_m[0].z() + 0.001;  // legs 1 mm above the ground
  ic.v_ENU_m_s = {0.0, 0.0, -touchdown_m_s};
  m.reset(ic);
  bool touched = false;
  double max_clearance_after_touch = -1.0;  // how high the legs rise again once they touched
  for (int i = 0; i < 750; ++i) {  // 3 s
    EXPECT_TRUE(m.step().ok());
    touched = touched || m.state().on_ground;
    if (touched) max_clearance_after_touch = std::max(max_clearance_after_touch, m.state().ground_clearance_m);
  }
  EXPECT_TRUE(touched);
  EXPECT_NEAR(m.state().p_ENU_m.z(), z_rest, 1e-3) << "sinks or floats";
  EXPECT_LT(m.state().v_ENU_m_s.norm(), 1e-3);
  EXPECT_LT(m.state().p_ENU_m.head<2>().norm(), 1e-3) << "slides";
  return max_clearance_after_touch;
}

/// Roll rate (FLU) after 0.1 s of a 1 rad/s pitch rate, without gravity, rotors at 800 rad/s.
double roll_rate_from_pitching(const VehicleConfig& vehicle) {
  WorldConfig world = default_world_config();
  world.gravity_m_s2 = 0.0;
  auto m = make(vehicle, world);
  InitialCondition ic;
  ic.p_ENU_m = {0.0, 0.0, 100.0};
  ic.w_FLU_rad_s = {0.0, 1.0, 0.0};
  ic.rotor_speed_rad_s.fill(800.0);
  m->reset(ic);
  m->set_motor_commands(all_motors(0.8));
  run_s(*m, 0.1);
  return m->state().w_FLU_rad_s.x();
}

TEST(Multicopter, GyroscopicCouplingComesFromTheRotorBodies) {
  // Pitching a vehicle whose rotors all spin the same way precesses it into roll, as
  // I dw/dt = -w x (I w + H_rotors) says: dw_x/dt = -w_y H_z / I_xx ~ -3.5 rad/s^2 here.
  VehicleConfig all_ccw = x500_vehicle_config();
  for (RotorConfig& r : all_ccw.rotors) {
    r.turning = Turning::Ccw;
    r.moment_constant_m = 0.0;  // no yaw drag torque either
  }
  const double h_z = 4 * all_ccw.rotors[0].inertia_kgm2.z() * 800.0;
  const double w_x = roll_rate_from_pitching(all_ccw);
  EXPECT_LT(w_x, 0.0);
  EXPECT_NEAR(w_x, -h_z / 0.0239 * 0.1, 0.3 * h_z / 0.0239 * 0.1);
  // The x500's counter-rotating pairs cancel their angular momentum: no precession.
  EXPECT_LT(std::abs(roll_rate_from_pitching(x500_vehicle_config())), 0.01);
}

TEST(Multicopter, LandsWithoutBounceOrSink) {
  auto m = make();
  EXPECT_LT(land(*m, 0.7), 0.002);  // PX4's default landing speed
  EXPECT_LT(land(*m, 1.5), 0.002);
  EXPECT_LT(land(*m, 3.0), 0.02);  // a hard landing: a few mm at most
}

TEST(Multicopter, FrictionHoldsSmallSideLoadAtRest) {
  auto m = make();
  const Eigen::Vector3d start = m->state().p_ENU_m;
  m->set_external_force_ENU_N({2.0, 1.0, 0.0});
  run_s(*m, 5.0);
  // It leans on its legs (the load acts 0.23 m above the skids: ~1.6 mm at the base), never slides.
  EXPECT_LT((m->state().p_ENU_m - start).head<2>().norm(), 3e-3);
  EXPECT_LT(m->state().v_ENU_m_s.norm(), 1e-4);
}

TEST(Multicopter, FrictionGivesWayToLargeSideLoad) {
  // A push above mu * m * g slides the vehicle; applied low enough (through the CoM) not to tip it.
  VehicleConfig v = x500_vehicle_config();
  v.landing_gear.friction_coefficient = 0.1;  // slides at ~2 N
  auto m = make(v);
  m->set_external_force_ENU_N({4.0, 0.0, 0.0});
  run_s(*m, 1.0);
  EXPECT_GT(m->state().p_ENU_m.x(), 0.1);
}

TEST(Multicopter, WindDragsAHoveringVehicleDownwind) {
  WorldConfig w = default_world_config();
  w.wind.velocity_ENU_m_s = {5.0, 0.0, 0.0};  // blowing towards east
  auto m = make(x500_vehicle_config(), w);
  start_hovering(*m, 5.0);
  run_s(*m, 1.0);
  EXPECT_GT(m->state().v_ENU_m_s.x(), 0.1);
  EXPECT_NEAR(m->state().wind_ENU_m_s.x(), 5.0, 1e-12);
}

TEST(Multicopter, SameSeedAndInputsGiveBitIdenticalStates) {
  WorldConfig w = default_world_config();
  w.wind.gust_sigma_m_s = {2.0, 2.0, 0.5};
  auto a = make(x500_vehicle_config(), w, 42);
  auto b = make(x500_vehicle_config(), w, 42);
  auto c = make(x500_vehicle_config(), w, 43);
  bool c_differs = false;
  for (int i = 0; i < 1000; ++i) {
    const double u = 0.8 + 0.05 * std::sin(i * 0.01);
    for (Multicopter* m : {a.get(), b.get(), c.get()}) {
      m->set_motor_commands({{u, u * 0.99, u, u * 1.01}, true});
      ASSERT_TRUE(m->step().ok());
    }
    ASSERT_EQ(a->state().p_ENU_m, b->state().p_ENU_m) << "step " << i;
    ASSERT_EQ(a->state().q_FLU_to_ENU.coeffs(), b->state().q_FLU_to_ENU.coeffs());
    ASSERT_EQ(a->state().v_ENU_m_s, b->state().v_ENU_m_s);
    ASSERT_EQ(a->state().w_FLU_rad_s, b->state().w_FLU_rad_s);
    c_differs = c_differs || c->state().p_ENU_m != a->state().p_ENU_m;
  }
  EXPECT_TRUE(c_differs) << "another seed gives other gusts";
  // A reset run repeats the first.
  const Eigen::Vector3d end = a->state().p_ENU_m;
  a->reset();
  for (int i = 0; i < 1000; ++i) {
    const double u = 0.8 + 0.05 * std::sin(i * 0.01);
    a->set_motor_commands({{u, u * 0.99, u, u * 1.01}, true});
    ASSERT_TRUE(a->step().ok());
  }
  EXPECT_EQ(a->state().p_ENU_m, end);
}

TEST(Multicopter, BadCommandsAreClampedAndCounted) {
  auto m = make();
  const double nan = std::nan("");
  m->set_motor_commands({{nan, 1.5, -0.2, INFINITY}, true});
  EXPECT_EQ(m->input_counters().non_finite, 2u);
  EXPECT_EQ(m->input_counters().out_of_range, 2u);
  run_s(*m, 0.5);
  // Only motor 1 runs, at full speed (1.5 clamped to 1).
  EXPECT_NEAR(m->state().rotor_speed_rad_s[1], 1000.0, 1.0);
  EXPECT_LT(m->state().rotor_speed_rad_s[0], 1.0);  // only dragged by the frame's reaction yaw
  EXPECT_LT(m->state().rotor_speed_rad_s[2], 1.0);  // only dragged by the frame's reaction yaw
  EXPECT_LT(m->state().rotor_speed_rad_s[3], 1.0);  // only dragged by the frame's reaction yaw
  EXPECT_TRUE(m->state().p_ENU_m.allFinite());
}

TEST(Multicopter, DisarmedStopsTheMotors) {
  auto m = make();
  start_hovering(*m, 5.0);
  MotorCommands c = all_motors(0.9);
  c.armed = false;
  m->set_motor_commands(c);
  run_s(*m, 0.3);
  for (double w : m->state().rotor_speed_rad_s) EXPECT_LT(w, 769.4 * std::exp(-0.3 / 0.025) * 1.5);
}

TEST(Multicopter, MotorSpeedFollowsTheFirstOrderLag) {
  auto m = make();
  start_hovering(*m, 50.0);
  m->set_motor_commands(all_motors(1.0));
  ASSERT_TRUE(m->step().ok());  // the command acts in the very next step
  const double w0 = 769.4, dt = 0.004, tau_up = 0.0125;
  const double expected = 1000.0 + (w0 - 1000.0) * std::exp(-dt / tau_up);
  EXPECT_NEAR(m->state().rotor_speed_rad_s[0], expected, 2.0);
  run_s(*m, 0.1);
  EXPECT_NEAR(m->state().rotor_speed_rad_s[0], 1000.0, 1.0);
}

TEST(Multicopter, BlowUpIsReportedNotPropagated) {
  VehicleConfig v = x500_vehicle_config();
  v.landing_gear.stiffness_N_m = 1e9;  // absurd: explicit integration at 4 ms cannot hold it
  auto m = make(v);
  Status s = Ok{};
  int steps = 0;
  for (; steps < 2000 && s.ok(); ++steps) s = m->step();
  ASSERT_FALSE(s.ok()) << "no blow-up detected";
  EXPECT_NE(s.error().message.find("physics blew up in step"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("p_ENU_m"), std::string::npos);
  const VehicleState frozen = m->state();
  EXPECT_TRUE(frozen.p_ENU_m.allFinite());
  EXPECT_TRUE(frozen.v_ENU_m_s.allFinite());
  EXPECT_LE(frozen.v_ENU_m_s.norm(), default_world_config().physics.max_speed_m_s);
  EXPECT_FALSE(m->step().ok());  // stays failed
  EXPECT_EQ(m->state().step, frozen.step);
  m->reset();
  EXPECT_EQ(m->state().step, 0u);
}

TEST(Multicopter, InvalidConfigIsRefusedNamingTheKey) {
  VehicleConfig v = x500_vehicle_config();
  v.rotors[2].time_constant_up_s = -1.0;
  auto created = Multicopter::create(v, default_world_config(), 1);
  ASSERT_FALSE(created.ok());
  EXPECT_NE(created.error().message.find("rotors[2].time_constant_up_s: must be > 0 (got -1.0)"), std::string::npos)
      << created.error().message;
}

TEST(Multicopter, LongerOuterStepUsesSubsteps) {
  WorldConfig w = default_world_config();
  w.physics.step_s = 0.01;  // 3 sub-steps of 3.33 ms
  auto m = make(x500_vehicle_config(), w);
  InitialCondition ic = m->resting_on_ground();
  ic.p_ENU_m.z() += 10.0;
  m->reset(ic);
  run_s(*m, 1.0);
  EXPECT_NEAR(m->state().time_s, 1.0, 1e-9);
  EXPECT_NEAR(m->state().p_ENU_m.z(), ic.p_ENU_m.z() - 0.5 * 9.80665, 0.05);
  EXPECT_NEAR(m->state().v_ENU_m_s.z(), -9.80665, 1e-6);
}

}  // namespace
}  // namespace hitl::model
