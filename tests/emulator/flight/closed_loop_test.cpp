// The CI scenario in process, over seeds: estimator convergence (arm denied before, with the
// reason), arm, takeoff to 2.5 m, hold 10 s within +-0.3 m (truth), 5 m north by pitch stick and
// back, land, auto-disarm. Every seed must pass; the figures are printed per seed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "engine/frames/frames.h"
#include "tests/emulator/flight/sim_loop.h"

namespace hitl::flight::test {
namespace {

struct Figures {
  double ready_s = 0.0;
  std::string early_reason;
  double rest_tilt_err_deg = 0.0;
  double rest_att_err_deg = 0.0, rest_bias_tilt_deg = 0.0, rest_pos_err_m = 0.0;
  double takeoff_s = 0.0;
  double hold_z_err_max_m = 0.0, hold_xy_drift_max_m = 0.0;
  double flight_att_err_max_deg = 0.0, flight_pos_err_max_m = 0.0, flight_gps_wander_max_m = 0.0;
  double north_reached_m = 0.0, back_m = 0.0, transit_z_err_max_m = 0.0;
  double land_to_disarm_s = 0.0;
  bool disarmed_by_landing = false;
  double yaw_after_turn_deg = 0.0;
};

/// Estimated minus true horizontal position, against what the GPS error alone explains: the
/// estimate's origin is the first fix, whose wandering error the truth does not have.
double horizontal_error_m(SimLoop& sim) {
  return (sim.core().estimate().p_NED_m.head<2>() - sim.truth().p_NED_m.head<2>()).norm();
}

Figures fly(std::uint64_t seed) {
  Figures f;
  SimLoop sim(seed);
  FlightCore& core = sim.core();

  // Before convergence: arming is denied with a reason.
  sim.run_s(1.0);
  const CommandReply early = core.arm();
  EXPECT_EQ(early.result, CommandResult::Denied);
  EXPECT_FALSE(core.armed());
  f.early_reason = early.reason;
  EXPECT_EQ(f.early_reason.rfind("Preflight Fail: ", 0), 0u) << f.early_reason;

  EXPECT_TRUE(sim.run_until([&] { return core.preflight_check().ready; }, 20.0)) << core.preflight_check().reason;
  f.ready_s = sim.time_s();
  sim.run_s(1.0);
  f.rest_att_err_deg = sim.attitude_error_deg();
  f.rest_tilt_err_deg = sim.tilt_error_deg();
  f.rest_bias_tilt_deg = sim.accel_bias_tilt_deg();
  const Eigen::Vector3d gps_err_at_ready = sim.sensors().gps().position_error_ENU_m();
  f.rest_pos_err_m = horizontal_error_m(sim);

  // Arm, take off to MIS_TAKEOFF_ALT (2.5 m above home).
  EXPECT_EQ(core.arm().result, CommandResult::Accepted);
  EXPECT_EQ(core.takeoff().result, CommandResult::Accepted);
  const double t0 = sim.time_s();
  const auto track_flight = [&] {
    f.flight_att_err_max_deg = std::max(f.flight_att_err_max_deg, sim.attitude_error_deg());
    f.flight_pos_err_max_m = std::max(f.flight_pos_err_max_m, horizontal_error_m(sim));
    f.flight_gps_wander_max_m =
        std::max(f.flight_gps_wander_max_m, (sim.sensors().gps().position_error_ENU_m() - gps_err_at_ready).head<2>().norm());
  };
  EXPECT_TRUE(sim.run_until([&] { track_flight(); return core.mode() == FlightMode::Hold; }, 15.0));
  f.takeoff_s = sim.time_s() - t0;
  EXPECT_EQ(core.landed_state(), LandedState::InAir);

  // Settle, then hold 10 s.
  sim.run_until([&] { track_flight(); return false; }, 3.0);
  const Eigen::Vector2d hold_xy = sim.truth().p_NED_m.head<2>();
  sim.run_until([&] {
    track_flight();
    f.hold_z_err_max_m = std::max(f.hold_z_err_max_m, std::abs(sim.truth_height_m() - 2.5));
    f.hold_xy_drift_max_m = std::max(f.hold_xy_drift_max_m, (sim.truth().p_NED_m.head<2>() - hold_xy).norm());
    return false;
  }, 10.0);

  // Position mode; pitch forward until 5 m north, release, then back.
  EXPECT_EQ(core.set_mode(FlightMode::Position).result, CommandResult::Accepted);
  StickInput sticks;
  const auto with_sticks = [&](double pitch, double yaw = 0.0) {
    sticks.time_us = sim.time_us();
    sticks.pitch = pitch;
    sticks.yaw = yaw;
    core.handle_sticks(sticks);
    track_flight();
    f.transit_z_err_max_m = std::max(f.transit_z_err_max_m, std::abs(sim.truth_height_m() - 2.5));
  };
  // The engine's x500 rests facing east (q_FLU_to_ENU = identity): yaw left to north first.
  EXPECT_TRUE(sim.run_until([&] { with_sticks(0.0, -0.4); return std::abs(core.estimate().yaw_rad) < 0.05; }, 10.0));
  sim.run_until([&] { with_sticks(0.0); return false; }, 3.0);
  f.yaw_after_turn_deg = frames::euler_from(sim.truth().q_FRD_to_NED).yaw_rad * 180.0 / 3.141592653589793;
  const double north0_m = sim.truth().p_NED_m.x();
  EXPECT_TRUE(sim.run_until([&] { 
    with_sticks(0.3);  // release early enough to brake at MPC_ACC_HOR (a pilot would)
    const double v = core.estimate().v_NED_m_s.x();
    return core.estimate().p_NED_m.x() - north0_m + v * v / (2.0 * 3.0) + 0.4 * v >= 5.0; }, 20.0));
  sim.run_until([&] { with_sticks(0.0); return false; }, 5.0);
  f.north_reached_m = sim.truth().p_NED_m.x() - north0_m;
  EXPECT_TRUE(sim.run_until([&] { 
    with_sticks(-0.3);
    const double v = core.estimate().v_NED_m_s.x();
    return core.estimate().p_NED_m.x() - north0_m - v * v / (2.0 * 3.0) + 0.4 * v <= 0.0; }, 20.0));
  sim.run_until([&] { with_sticks(0.0); return false; }, 5.0);
  f.back_m = sim.truth().p_NED_m.x() - north0_m;

  // Land and auto-disarm.
  EXPECT_EQ(core.land().result, CommandResult::Accepted);
  const double t_land = sim.time_s();
  EXPECT_TRUE(sim.run_until([&] { track_flight(); return !core.armed(); }, 20.0));
  f.land_to_disarm_s = sim.time_s() - t_land;
  for (const StatusMessage& m : core.take_messages()) {
    if (m.text == "Disarmed by landing") f.disarmed_by_landing = true;
  }
  EXPECT_LT(sim.truth_height_m(), 0.05);
  return f;
}

// PX4 reports TAKEOFF only while its takeoff runs: a pilot who switches to Position mode during the
// climb (as hitl's trajectory pilot does) flies IN_AIR from then on, not "taking off" to the end.
TEST(FlightClosedLoop, LeavingTakeoffInTheClimbIsInAir) {
  SimLoop sim(3);
  FlightCore& core = sim.core();
  ASSERT_TRUE(sim.run_until([&] { return core.preflight_check().ready; }, 20.0));
  ASSERT_EQ(core.arm().result, CommandResult::Accepted);
  ASSERT_EQ(core.takeoff().result, CommandResult::Accepted);
  ASSERT_TRUE(sim.run_until([&] { return sim.truth_height_m() > 1.0; }, 15.0));
  EXPECT_EQ(core.landed_state(), LandedState::Takeoff);
  EXPECT_EQ(core.set_mode(FlightMode::Position).result, CommandResult::Accepted);
  sim.run_s(2.0);
  EXPECT_EQ(core.landed_state(), LandedState::InAir);
  EXPECT_EQ(core.land().result, CommandResult::Accepted);  // and it lands as from any flight
  EXPECT_TRUE(sim.run_until([&] { return !core.armed(); }, 20.0));
}

TEST(FlightClosedLoop, EverySeedFliesTheCiScenario) {
  constexpr int kSeeds = 10;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Figures f = fly(static_cast<std::uint64_t>(seed));
    std::printf(
        "seed %2d: ready %.1f s ('%s'), rest tilt %.2f att %.2f deg (accel-bias tilt %.2f), rest pos %.2f m | takeoff %.1f s, "
        "hold |dz| %.3f m, xy drift %.2f m | north %.2f m, back %.2f m, transit |dz| %.2f m | flight att max %.2f "
        "deg, pos err max %.2f m (gps wander %.2f) | yaw after turn %.1f deg | land->disarm %.1f s\n",
        seed, f.ready_s, f.early_reason.c_str(), f.rest_tilt_err_deg, f.rest_att_err_deg, f.rest_bias_tilt_deg, f.rest_pos_err_m,
        f.takeoff_s, f.hold_z_err_max_m, f.hold_xy_drift_max_m, f.north_reached_m, f.back_m, f.transit_z_err_max_m,
        f.flight_att_err_max_deg, f.flight_pos_err_max_m, f.flight_gps_wander_max_m, f.yaw_after_turn_deg, f.land_to_disarm_s);
    EXPECT_LT(f.ready_s, 15.0);
    // The accelerometer's turn-on bias (sigma 0.196 m/s^2 per axis) tilts any accel-levelled
    // estimate by b_xy / g, unobservable at rest, and that tilt leaks into the magnetometer heading
    // through the field's 63 deg inclination (x tan 63 deg ~ 2): the bounds carry that allowance.
    const double bias_allowance_deg = 2.3 * f.rest_bias_tilt_deg;
    EXPECT_LT(f.rest_tilt_err_deg, 1.0 + f.rest_bias_tilt_deg);
    EXPECT_LT(f.rest_att_err_deg, 2.0 + bias_allowance_deg);
    EXPECT_LT(f.hold_z_err_max_m, 0.3);
    EXPECT_LT(f.flight_att_err_max_deg, 5.0 + bias_allowance_deg);
    EXPECT_LT(f.flight_pos_err_max_m, 1.0 + f.flight_gps_wander_max_m);
    // The pilot flies by the estimate; the truth differs by the GPS's wandering error (sigma 0.5 m
    // per axis, 60 s correlation), which no GPS-aided estimator can remove.
    EXPECT_NEAR(f.north_reached_m, 5.0, 1.0 + f.flight_gps_wander_max_m);
    EXPECT_NEAR(f.back_m, 0.0, 1.0 + f.flight_gps_wander_max_m);
    EXPECT_LT(f.transit_z_err_max_m, 0.5);
    EXPECT_TRUE(f.disarmed_by_landing);
    EXPECT_LT(f.land_to_disarm_s, 12.0);
  }
}

}  // namespace
}  // namespace hitl::flight::test
