// Stabilized (PX4 main mode 7) in the closed loop: sticks are attitude and thrust, not velocity.
// Level sticks at mid throttle hover (MPC_THR_HOVER); a pitch stick tilts the x500 by
// stick x MPC_MAN_TILT_MAX and it accelerates along its heading; releasing levels it; throttle up
// climbs; losing the sticks in the air falls back to Hold. Plus the throttle curve in units.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "emulator/flight/manual_attitude.h"
#include "engine/frames/frames.h"
#include "tests/emulator/flight/sim_loop.h"

namespace hitl::flight::test {
namespace {

constexpr double kRadToDeg = 180.0 / 3.141592653589793;

TEST(ManualThrust, RescalesAroundHoverThrust) {
  FlightParams p;
  EXPECT_DOUBLE_EQ(manual_thrust(0.0, p), p.MPC_MANTHR_MIN);
  EXPECT_DOUBLE_EQ(manual_thrust(0.5, p), p.MPC_THR_HOVER);
  EXPECT_DOUBLE_EQ(manual_thrust(1.0, p), p.MPC_THR_MAX);
  EXPECT_NEAR(manual_thrust(0.75, p), 0.5 * (p.MPC_THR_HOVER + p.MPC_THR_MAX), 1e-6);
  EXPECT_DOUBLE_EQ(manual_thrust(7.0, p), p.MPC_THR_MAX);  // out-of-range sticks are clamped
}

TEST(ManualAttitude, PitchForwardIsNoseDownAndTiltIsLimited) {
  FlightParams p;
  ManualAttitudeSetpoint m;
  m.reset(0.0);
  StickInput s;
  s.pitch = 1.0;
  s.roll = 1.0;  // the combined tilt is still MPC_MAN_TILT_MAX
  const auto sp = m.update(s, p, 0.004);
  const auto e = frames::euler_from(sp.q_sp_FRD_to_NED);
  EXPECT_LT(e.pitch_rad, 0.0);
  EXPECT_GT(e.roll_rad, 0.0);
  const Eigen::Vector3d z_body = sp.q_sp_FRD_to_NED * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::acos(z_body.z()) * kRadToDeg, p.MPC_MAN_TILT_MAX, 0.01);
}

TEST(FlightStabilized, SticksAreAttitudeAndThrust) {
  SimLoop sim(1);
  FlightCore& core = sim.core();
  ASSERT_TRUE(sim.run_until([&] { return core.preflight_check().ready; }, 25.0)) << core.preflight_check().reason;
  ASSERT_EQ(core.arm().result, CommandResult::Accepted);
  ASSERT_EQ(core.takeoff().result, CommandResult::Accepted);
  ASSERT_TRUE(sim.run_until([&] { return core.mode() == FlightMode::Hold; }, 15.0));
  sim.run_s(2.0);

  StickInput sticks;
  const auto hold_sticks = [&](double pitch, double throttle) {
    sticks.time_us = sim.time_us();
    sticks.pitch = pitch;
    sticks.throttle = throttle;
    core.handle_sticks(sticks);
  };
  const CommandReply no_sticks = core.set_mode(FlightMode::Stabilized);
  EXPECT_EQ(no_sticks.result, CommandResult::Denied);
  EXPECT_NE(no_sticks.reason.find("no manual control"), std::string::npos) << no_sticks.reason;
  hold_sticks(0.0, 0.5);
  ASSERT_EQ(core.set_mode(FlightMode::Stabilized).result, CommandResult::Accepted);
  EXPECT_EQ(core.custom_mode(), 0x00070000u);

  // Level, mid throttle: hovers (no altitude hold, so a slow drift is allowed).
  const double z0 = sim.truth_height_m();
  sim.run_until([&] { hold_sticks(0.0, 0.5); return false; }, 3.0);
  EXPECT_NEAR(sim.truth_height_m(), z0, 1.0);
  const auto level = frames::euler_from(sim.truth().q_FRD_to_NED);
  EXPECT_LT(std::abs(level.roll_rad * kRadToDeg), 2.0);
  EXPECT_LT(std::abs(level.pitch_rad * kRadToDeg), 2.0);

  // Pitch stick 0.3: about 10.5 deg nose down, accelerating along the heading (east at spawn).
  const Eigen::Vector3d p0 = sim.truth().p_NED_m;
  sim.run_until([&] { hold_sticks(0.3, 0.5); return false; }, 1.5);
  const double pitch_deg = frames::euler_from(sim.truth().q_FRD_to_NED).pitch_rad * kRadToDeg;
  EXPECT_NEAR(pitch_deg, -0.3 * core.params().MPC_MAN_TILT_MAX, 2.0);
  const Eigen::Vector3d heading_NED = sim.truth().q_FRD_to_NED * Eigen::Vector3d::UnitX();
  const Eigen::Vector2d moved = (sim.truth().p_NED_m - p0).head<2>();
  EXPECT_GT(moved.dot(heading_NED.head<2>().normalized()), 0.5);

  // Released: levels within a second.
  sim.run_until([&] { hold_sticks(0.0, 0.5); return false; }, 1.0);
  EXPECT_LT(std::abs(frames::euler_from(sim.truth().q_FRD_to_NED).pitch_rad * kRadToDeg), 2.0);

  // Throttle up climbs.
  const double z1 = sim.truth_height_m();
  sim.run_until([&] { hold_sticks(0.0, 0.8); return false; }, 1.5);
  EXPECT_GT(sim.truth_height_m() - z1, 0.5);
  hold_sticks(0.0, 0.5);

  // Sticks lost (no RC_CHANNELS_OVERRIDE for COM_RC_LOSS_T): Hold, said in words.
  core.take_messages();
  ASSERT_TRUE(sim.run_until([&] { return core.mode() == FlightMode::Hold; }, 2.0));
  bool said = false;
  for (const auto& m : core.take_messages()) said = said || m.text == "Manual control lost: switching to Hold";
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace hitl::flight::test
