// Allocation: torque directions from the spec's geometry, the thrust-curve inverse, saturation
// priorities, and on the engine's x500 the rotations the engine tests associate with each motor set
// (front motors faster -> nose up, left faster -> roll right, CCW pair faster -> yaw right).
#include "emulator/flight/mixer.h"

#include <cmath>

#include <gtest/gtest.h>

#include "engine/frames/frames.h"
#include "engine/model/multicopter.h"
#include "engine/model/x500_defaults.h"

namespace hitl::flight {
namespace {

Mixer x500_mixer() { return Mixer(geometry_from(FlightParams{})); }

TEST(Mixer, TorqueDirectionsFollowTheGeometry) {
  const Mixer mixer = x500_mixer();
  const Eigen::Matrix4d& M = mixer.mix_matrix();  // rows: motors 0 FR, 1 BL, 2 FL, 3 BR
  // +roll (right side down): left motors (1, 2) faster.
  EXPECT_LT(M(0, 0), 0.0);
  EXPECT_GT(M(1, 0), 0.0);
  EXPECT_GT(M(2, 0), 0.0);
  EXPECT_LT(M(3, 0), 0.0);
  // +pitch (nose up): front motors (0, 2) faster.
  EXPECT_GT(M(0, 1), 0.0);
  EXPECT_LT(M(1, 1), 0.0);
  EXPECT_GT(M(2, 1), 0.0);
  EXPECT_LT(M(3, 1), 0.0);
  // +yaw (clockwise): CCW motors (0, 1) faster.
  EXPECT_GT(M(0, 2), 0.0);
  EXPECT_GT(M(1, 2), 0.0);
  EXPECT_LT(M(2, 2), 0.0);
  EXPECT_LT(M(3, 2), 0.0);
  // PX4 normalization: roll/pitch entries 1/sqrt(2), yaw 1, thrust 1.
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(std::abs(M(i, 0)), std::sqrt(0.5), 1e-9);
    EXPECT_NEAR(std::abs(M(i, 1)), std::sqrt(0.5), 1e-9);
    EXPECT_NEAR(std::abs(M(i, 2)), 1.0, 1e-9);
    EXPECT_NEAR(M(i, 3), 1.0, 1e-9);
  }
}

TEST(Mixer, HoverThrustMapsToTheEngineHoverCommand) {
  // x500.md: hover at u = 0.769 with thrust ~ u^2 -> thrust fraction 0.592.
  const double u_h = model::hover_command(model::x500_vehicle_config(), model::default_world_config());
  const MixerOutput out = x500_mixer().mix(Eigen::Vector3d::Zero(), u_h * u_h, 1.0);
  for (double u : out.u) EXPECT_NEAR(u, u_h, 1e-9);
  EXPECT_NEAR(motor_command_from_thrust(0.25, 1.0), 0.5, 1e-12);
  EXPECT_NEAR(motor_command_from_thrust(0.25, 0.0), 0.25, 1e-12);
  const double f = 0.3, u = motor_command_from_thrust(0.4, f);
  EXPECT_NEAR((1 - f) * u + f * u * u, 0.4, 1e-12);
}

TEST(Mixer, YawYieldsFirstRollPitchKeepTheirRatio) {
  const Mixer m = x500_mixer();
  // Full yaw at high thrust: yaw is cut, thrust and roll/pitch kept.
  const MixerOutput a = m.mix(Eigen::Vector3d(0.1, 0.0, 1.0), 0.9, 0.0);
  EXPECT_TRUE(a.saturated_positive[2]);
  EXPECT_FALSE(a.saturated_positive[0]);
  for (double t : a.thrust) EXPECT_LE(t, 1.0);
  EXPECT_NEAR((a.thrust[1] + a.thrust[2]) - (a.thrust[0] + a.thrust[3]), 4 * 0.1 * std::sqrt(0.5), 1e-9);
  // Huge roll: scaled to fit, flagged.
  const MixerOutput b = m.mix(Eigen::Vector3d(3.0, 0.0, 0.0), 0.5, 0.0);
  EXPECT_TRUE(b.saturated_positive[0]);
  for (double t : b.thrust) {
    EXPECT_GE(t, 0.0);
    EXPECT_LE(t, 1.0);
  }
}

/// Body rates after 0.2 s of hover plus `torque` through the mixer, on the engine's x500.
Eigen::Vector3d engine_rates_FRD(const Eigen::Vector3d& torque) {
  const model::VehicleConfig vehicle = model::x500_vehicle_config();
  const model::WorldConfig world = model::default_world_config();
  auto m = std::move(model::Multicopter::create(vehicle, world, 1).value());
  const double u_h = model::hover_command(vehicle, world);
  model::InitialCondition ic;
  ic.p_ENU_m = {0.0, 0.0, 5.0};
  ic.rotor_speed_rad_s.fill(u_h * 1000.0);
  m->reset(ic);
  const MixerOutput out = x500_mixer().mix(torque, u_h * u_h, 1.0);
  m->set_motor_commands({out.u, true});
  for (int i = 0; i < 50; ++i) EXPECT_TRUE(m->step().ok());
  return frames::flu_to_frd(m->state().w_FLU_rad_s);
}

TEST(Mixer, EngineRotatesTheWayTheTorqueAsks) {
  const Eigen::Vector3d roll = engine_rates_FRD({0.05, 0.0, 0.0});
  EXPECT_GT(roll.x(), 0.2);
  EXPECT_LT(std::abs(roll.y()), 0.1 * roll.x());
  const Eigen::Vector3d pitch = engine_rates_FRD({0.0, 0.05, 0.0});
  EXPECT_GT(pitch.y(), 0.2);
  EXPECT_LT(std::abs(pitch.x()), 0.1 * pitch.y());
  const Eigen::Vector3d yaw = engine_rates_FRD({0.0, 0.0, 0.1});
  EXPECT_GT(yaw.z(), 0.05);
  EXPECT_LT(std::abs(yaw.x()) + std::abs(yaw.y()), 0.2 * yaw.z());
}

}  // namespace
}  // namespace hitl::flight
