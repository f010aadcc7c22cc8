// The model's pure parts: ISA, motor model, ground contact, random streams, wind.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/model/atmosphere.h"
#include "engine/model/ground_contact.h"
#include "engine/model/motor_model.h"
#include "engine/model/multicopter.h"
#include "engine/model/random_stream.h"
#include "engine/model/wind.h"
#include "engine/model/x500_defaults.h"
#include "tests/support/statistics.h"

namespace hitl::model {
namespace {

using test::sample_sigma;

TEST(Atmosphere, IsaMatchesTheX500Formula) {
  const AtmosphereConfig isa = default_world_config().atmosphere;
  for (double h : {0.0, 488.0, 1000.0, 5000.0}) {
    EXPECT_NEAR(isa_pressure_Pa(isa, h), 101325.0 * std::pow(1.0 - 2.25577e-5 * h, 5.25588), 0.05) << h;
    EXPECT_NEAR(isa_altitude_m(isa, isa_pressure_Pa(isa, h)), h, 1e-6);
  }
  EXPECT_NEAR(isa_temperature_degC(isa, 0.0), 15.0, 1e-12);
  EXPECT_NEAR(isa_temperature_degC(isa, 1000.0), 8.5, 1e-12);
  // About 12 Pa per metre near the ground.
  EXPECT_NEAR(isa_pressure_Pa(isa, 0.0) - isa_pressure_Pa(isa, 1.0), 12.0, 0.1);
}

TEST(MotorCommand, NonFiniteBecomesZeroAndOutOfRangeIsClampedOnce) {
  EXPECT_EQ(check_motor_command(0.5).u, 0.5);
  EXPECT_EQ(check_motor_command(0.5).fix, CommandFix::None);
  EXPECT_EQ(check_motor_command(0.0).fix, CommandFix::None);
  EXPECT_EQ(check_motor_command(1.0).fix, CommandFix::None);
  EXPECT_EQ(check_motor_command(1.5).u, 1.0);
  EXPECT_EQ(check_motor_command(1.5).fix, CommandFix::OutOfRange);
  EXPECT_EQ(check_motor_command(-0.1).u, 0.0);
  EXPECT_EQ(check_motor_command(-0.1).fix, CommandFix::OutOfRange);
  for (double bad : {std::nan(""), double{INFINITY}, -double{INFINITY}}) {
    EXPECT_EQ(check_motor_command(bad).u, 0.0);
    EXPECT_EQ(check_motor_command(bad).fix, CommandFix::NonFinite);
  }
}

TEST(MotorModel, CommandMapsToSpeedReference) {
  RotorConfig r = x500_vehicle_config().rotors[0];
  EXPECT_DOUBLE_EQ(omega_reference_rad_s(r, 0.769, true), 769.0);
  EXPECT_DOUBLE_EQ(omega_reference_rad_s(r, 0.769, false), 0.0);
  EXPECT_DOUBLE_EQ(omega_reference_rad_s(r, 1.0, true), 1000.0);
  r.input_offset = 0.1;
  r.zero_position_armed_rad_s = 50.0;
  EXPECT_DOUBLE_EQ(omega_reference_rad_s(r, 0.5, true), 650.0);
  EXPECT_DOUBLE_EQ(omega_reference_rad_s(r, 1.0, true), 1000.0);  // clamped to max_rot_velocity
}

TEST(MotorModel, LagUsesUpAndDownTimeConstants) {
  const RotorConfig r = x500_vehicle_config().rotors[0];
  EXPECT_NEAR(next_rotor_speed_rad_s(r, 0.0, 1000.0, 0.0125), 1000.0 * (1.0 - std::exp(-1.0)), 1e-9);
  EXPECT_NEAR(next_rotor_speed_rad_s(r, 1000.0, 0.0, 0.025), 1000.0 * std::exp(-1.0), 1e-9);
}

TEST(MotorModel, ThrustDragTorqueAndRotorDrag) {
  const RotorConfig ccw = x500_vehicle_config().rotors[0];
  const RotorConfig cw = x500_vehicle_config().rotors[2];
  const Eigen::Vector3d up(0, 0, 1);
  const RotorLoads hover = rotor_loads(ccw, 1000.0, up, Eigen::Vector3d::Zero());
  EXPECT_NEAR(hover.force_at_hub_ENU_N.z(), 8.54858, 1e-9);  // kF * 1000^2
  // Drag torque kM * thrust against the spin: CCW rotor turns the frame clockwise (-z), CW the other way.
  EXPECT_NEAR(hover.torque_on_frame_ENU_Nm.z(), -0.016 * 8.54858, 1e-12);
  EXPECT_NEAR(rotor_loads(cw, 1000.0, up, Eigen::Vector3d::Zero()).torque_on_frame_ENU_Nm.z(), 0.016 * 8.54858, 1e-12);
  // Flying east through still air: in-plane drag and rolling moment point west, thrust unchanged.
  const RotorLoads moving = rotor_loads(ccw, 1000.0, up, Eigen::Vector3d(5.0, 0.0, 0.0));
  EXPECT_NEAR(moving.force_at_hub_ENU_N.x(), -1000.0 * 8.06428e-05 * 5.0, 1e-12);
  EXPECT_NEAR(moving.torque_on_frame_ENU_Nm.x(), -1000.0 * 1e-06 * 5.0, 1e-12);
  EXPECT_NEAR(moving.force_at_hub_ENU_N.z(), 8.54858, 1e-9);
  // Climbing at 12.5 m/s through the air halves the thrust; at 25 m/s none is left.
  EXPECT_NEAR(rotor_loads(ccw, 1000.0, up, Eigen::Vector3d(0, 0, 12.5)).force_at_hub_ENU_N.z(), 8.54858 / 2, 1e-9);
  EXPECT_NEAR(rotor_loads(ccw, 1000.0, up, Eigen::Vector3d(0, 0, 30.0)).force_at_hub_ENU_N.z(), 0.0, 1e-12);
}

TEST(GroundContact, PushesOnlyWhenTouchingAndNeverPulls) {
  const LandingGearConfig gear = x500_vehicle_config().landing_gear;
  const ContactAnchor none;
  EXPECT_EQ(ground_contact_force_ENU_N(gear, {0, 0, 0.01}, {0, 0, -1}, none), Eigen::Vector3d::Zero());
  EXPECT_NEAR(ground_contact_force_ENU_N(gear, {0, 0, -0.001}, {0, 0, 0}, none).z(), gear.stiffness_N_m * 0.001, 1e-9);
  // The damping ramps in over damping_depth_m: a fifth of it at a fifth of that depth, all of it below.
  const double d = gear.damping_depth_m;
  EXPECT_NEAR(ground_contact_force_ENU_N(gear, {0, 0, -0.2 * d}, {0, 0, -0.1}, none).z(),
              gear.stiffness_N_m * 0.2 * d + 0.2 * gear.damping_N_s_m * 0.1, 1e-9);
  EXPECT_NEAR(ground_contact_force_ENU_N(gear, {0, 0, -2 * d}, {0, 0, -0.1}, none).z(),
              gear.stiffness_N_m * 2 * d + gear.damping_N_s_m * 0.1, 1e-9);
  // A frame point is a stiffer spring.
  const ContactPoint frame = contact_points(gear)[4];
  EXPECT_EQ(frame.p_FLU_m, gear.frame_points_FLU_m[0]);
  EXPECT_NEAR(ground_contact_force_ENU_N(gear, frame, {0, 0, -0.001}, {0, 0, 0}, none).z(), gear.frame_stiffness_N_m * 0.001, 1e-9);
  EXPECT_EQ(ground_contact_force_ENU_N(gear, {0, 0, -0.001}, {0, 0, 1.0}, none), Eigen::Vector3d::Zero());
}

TEST(GroundContact, StickSlipFrictionIsCappedAndAnchorFollowsSlip) {
  const LandingGearConfig gear = x500_vehicle_config().landing_gear;
  ContactAnchor anchor;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  update_contact_anchor(gear, {1.0, 2.0, -0.001}, zero, anchor);
  ASSERT_TRUE(anchor.set);
  EXPECT_EQ(anchor.p_EN_m, Eigen::Vector2d(1.0, 2.0));
  // Sticking: a small displacement pulls back with the tangential spring.
  const Eigen::Vector3d stick = ground_contact_force_ENU_N(gear, {1.0001, 2.0, -0.001}, zero, anchor);
  EXPECT_NEAR(stick.x(), -gear.tangential_stiffness_N_m * 0.0001, 1e-9);
  // Slipping: a large displacement is capped at mu * Fn, and the anchor is dragged along.
  const double fn = gear.stiffness_N_m * 0.001;
  const Eigen::Vector3d slip = ground_contact_force_ENU_N(gear, {1.5, 2.0, -0.001}, zero, anchor);
  EXPECT_NEAR(slip.x(), -gear.friction_coefficient * fn, 1e-9);
  update_contact_anchor(gear, {1.5, 2.0, -0.001}, zero, anchor);
  EXPECT_NEAR(anchor.p_EN_m.x(), 1.5 - gear.friction_coefficient * fn / gear.tangential_stiffness_N_m, 1e-12);
  // Lifting off forgets the anchor.
  update_contact_anchor(gear, {1.5, 2.0, 0.01}, zero, anchor);
  EXPECT_FALSE(anchor.set);
}

TEST(RandomStream, NamedStreamsAreDeterministicAndIndependent) {
  RandomStream a(7, "imu"), b(7, "imu"), c(7, "mag"), d(8, "imu");
  int same_c = 0, same_d = 0;
  for (int i = 0; i < 100; ++i) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    same_c += x == c.normal();
    same_d += x == d.normal();
  }
  EXPECT_EQ(same_c, 0);
  EXPECT_EQ(same_d, 0);
  EXPECT_EQ(a.normal(0.0), 0.0);  // zero noise is exact
}

TEST(RandomStream, GaussMarkovReachesItsStationarySigma) {
  RandomStream rng(3, "gm");
  const double sigma = 2.0, tau_s = 1.0, dt_s = 0.1;
  const double rw = random_walk_for_stationary_sigma(sigma, tau_s);
  double x = 0.0;
  std::vector<double> xs;
  for (int i = 0; i < 200000; ++i) {
    x = gauss_markov_step(x, dt_s, tau_s, rw, rng);
    xs.push_back(x);
  }
  EXPECT_NEAR(sample_sigma(xs), sigma, 0.05 * sigma);
}

TEST(Wind, MeanPlusSeededGusts) {
  WindConfig config = default_world_config().wind;
  config.velocity_ENU_m_s = {3.0, -1.0, 0.0};
  Wind calm(config, 1);
  EXPECT_EQ(calm.advance(0.004), Eigen::Vector3d(3.0, -1.0, 0.0));
  config.gust_sigma_m_s = {1.5, 1.5, 0.0};
  Wind gusty(config, 1), same(config, 1);
  std::vector<double> east;
  for (int i = 0; i < 100000; ++i) {
    const Eigen::Vector3d w = gusty.advance(0.02);
    ASSERT_EQ(w, same.advance(0.02));
    EXPECT_EQ(w.z(), 0.0);
    east.push_back(w.x());
  }
  EXPECT_NEAR(sample_sigma(east), 1.5, 0.1);
  gusty.reset();
  same.reset();
  EXPECT_EQ(gusty.advance(0.02), same.advance(0.02));
}

}  // namespace
}  // namespace hitl::model
