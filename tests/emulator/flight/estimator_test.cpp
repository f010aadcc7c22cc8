// The estimator alone on the engine's x500 at rest (motors off): alignment, the preflight reasons
// in order, convergence within seconds, attitude and position against truth, heading from the
// magnetometer at a non-trivial yaw, honest flags, and no GPS -> "no GPS fix".
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "engine/frames/frames.h"
#include "tests/emulator/flight/sim_loop.h"

namespace hitl::flight::test {
namespace {

using namespace estimator_flags;

TEST(Estimator, ConvergesAtRestAndTellsWhyNotBefore) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    SimLoop sim(seed);
    FlightCore& core = sim.core();
    sim.run_s(0.5);
    EXPECT_EQ(core.preflight_check().reason, "Preflight Fail: ekf2 not aligned");
    EXPECT_EQ(core.estimator_status().flags & kPosHorizAbs, 0);
    sim.run_s(4.0);
    EXPECT_EQ(core.preflight_check().reason, "Preflight Fail: ekf2 GPS checks pending");
    EXPECT_NE(core.estimator_status().flags & kAttitude, 0);
    EXPECT_NE(core.estimator_status().flags & kPosHorizRel, 0);
    EXPECT_TRUE(sim.run_until([&] { return core.preflight_check().ready; }, 10.0));
    sim.run_s(2.0);
    const EstimatorStatus s = core.estimator_status();
    for (std::uint16_t flag : {kAttitude, kVelocityHoriz, kVelocityVert, kPosHorizRel, kPosHorizAbs, kPosVertAbs,
                               kPredPosHorizRel, kPredPosHorizAbs}) {
      EXPECT_NE(s.flags & flag, 0) << flag;
    }
    for (std::uint16_t flag : {kConstPosMode, kGpsGlitch, kAccelError, kPosVertAgl}) EXPECT_EQ(s.flags & flag, 0) << flag;
    EXPECT_LT(s.vel_ratio, 0.1);
    EXPECT_LT(s.pos_horiz_ratio, 0.1);
    EXPECT_LT(s.pos_vert_ratio, 0.1);
    EXPECT_LT(s.mag_ratio, 0.1);
    EXPECT_LT(sim.tilt_error_deg(), 0.5 + sim.accel_bias_tilt_deg());
    const Estimate& e = core.estimate();
    EXPECT_LT((e.p_NED_m - sim.truth().p_NED_m).head<2>().norm(), 1.0);
    EXPECT_LT(std::abs(e.p_NED_m.z() - (sim.truth().p_NED_m.z() + sim.rest_height_m())), 0.3);
    EXPECT_LT(e.v_NED_m_s.norm(), 0.1);
    EXPECT_NEAR(e.lat_deg, sim.truth().lat_deg, 1.5e-5);  // ~1.5 m
    EXPECT_NEAR(e.lon_deg, sim.truth().lon_deg, 2.0e-5);
    EXPECT_NEAR(e.alt_msl_m, sim.truth().alt_m, 2.5);     // origin altitude from one GPS fix
    EXPECT_LT(e.gyro_bias_FRD_rad_s.norm(), 0.05);
  }
}

TEST(Estimator, HeadingComesFromTheMagnetometer) {
  const model::VehicleConfig vehicle = model::x500_vehicle_config();
  const model::WorldConfig world = model::default_world_config();
  auto probe = std::move(model::Multicopter::create(vehicle, world, 1).value());
  model::InitialCondition ic = probe->resting_on_ground();
  // Rest facing north-west: FLU->ENU rotated +135 deg about up (heading -45 deg = 315).
  ic.q_FLU_to_ENU = Eigen::Quaterniond(Eigen::AngleAxisd(3.0 * std::numbers::pi / 4.0, Eigen::Vector3d::UnitZ()));
  SimLoop sim(4, vehicle, world, &ic);
  sim.run_s(8.0);
  const double yaw_true = frames::euler_from(sim.truth().q_FRD_to_NED).yaw_rad;
  EXPECT_NEAR(yaw_true, -std::numbers::pi / 4.0, 1e-3);
  EXPECT_NEAR(wrap_pi(sim.core().estimate().yaw_rad - yaw_true), 0.0, 6.0 * std::numbers::pi / 180.0);
}

TEST(Estimator, NoGpsNoArming) {
  model::VehicleConfig vehicle = model::x500_vehicle_config();
  vehicle.sensors.gps.satellites = 3;  // the fix stays but fails the satellite check
  SimLoop sim(1, vehicle);
  sim.run_s(8.0);
  EXPECT_EQ(sim.core().preflight_check().reason, "Preflight Fail: not enough GPS Satellites");
  EXPECT_NE(sim.core().estimator_status().flags & kConstPosMode, 0);
  EXPECT_EQ(sim.core().arm().result, CommandResult::Denied);
  EXPECT_EQ(sim.core().arm(true).result, CommandResult::Accepted);  // forced
}

TEST(Commander, AutoDisarmWithoutTakeoff) {
  SimLoop sim(2);
  sim.run_until([&] { return sim.core().preflight_check().ready; }, 20.0);
  ASSERT_EQ(sim.core().arm().result, CommandResult::Accepted);
  sim.run_s(9.0);
  EXPECT_TRUE(sim.core().armed());
  EXPECT_EQ(sim.core().landed_state(), LandedState::OnGround);
  for (double u : sim.core().actuators().u) EXPECT_NEAR(u, sim.core().params().HITL_MOT_IDLE, 1e-6);
  sim.run_s(1.5);
  EXPECT_FALSE(sim.core().armed());
  bool said = false;
  for (const StatusMessage& m : sim.core().take_messages()) said = said || m.text == "Disarmed by auto preflight disarming";
  EXPECT_TRUE(said);
  EXPECT_EQ(sim.core().takeoff().result, CommandResult::Denied);
}

}  // namespace
}  // namespace hitl::flight::test
