// Touchdowns on the x500's legs (issue 20): 0.3-1.5 m/s vertical speed, up to 20 deg of tilt, motors
// stopped (or still pushing, level): every IMU sample stays within the IMU's range, the legs stop the vehicle
// over tens of milliseconds without sinking into the ground and without throwing it back up
// (rebound <= 1 cm); on its back the vehicle rests on the frame, even with the rotors at full speed;
// the IMU reads the step's mean, not its last instant.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "engine/model/multicopter.h"
#include "engine/model/touchdown_monitor.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/imu.h"

namespace hitl::model {
namespace {

constexpr double kG = 9.80665;

std::unique_ptr<Multicopter> make(const WorldConfig& world = default_world_config()) {
  auto created = Multicopter::create(x500_vehicle_config(), world, 1);
  EXPECT_TRUE(created.ok()) << (created.ok() ? "" : created.error().message);
  return std::move(created.value());
}

struct Touchdown {
  double peak_accel_m_s2 = 0;   ///< largest IMU accel norm (noise-free) after the touch
  double max_axis_m_s2 = 0;     ///< largest single axis
  double rebound_m = 0;         ///< highest clearance after the first touch
  double deepest_m = 0;         ///< lowest clearance (compression)
  double rest_clearance_m = 0;  ///< at the end
  uint64_t saturated = 0;
  uint64_t touchdowns = 0;
};

/// Drops the x500 with its lowest leg 1 mm above the ground at `speed_m_s` down, rolled and pitched
/// by `tilt_deg`, with the rotors at `thrust_fraction` of hover thrust (0: stopped), for 2 s.
Touchdown touch_down(double speed_m_s, double tilt_deg, double thrust_fraction, const WorldConfig& world = default_world_config()) {
  auto m = make(world);
  const VehicleConfig& v = m->vehicle_config();
  const double tilt_rad = tilt_deg * M_PI / 180.0;
  InitialCondition ic;
  ic.q_FLU_to_ENU = Eigen::AngleAxisd(tilt_rad, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(tilt_rad * 0.5, Eigen::Vector3d::UnitY());
  double lowest_m = 0;
  for (const auto& p : v.landing_gear.contact_points_FLU_m) lowest_m = std::min(lowest_m, (ic.q_FLU_to_ENU * p).z());
  ic.p_ENU_m = {0, 0, -lowest_m + 0.001};
  ic.v_ENU_m_s = {0, 0, -speed_m_s};
  const double u = thrust_fraction > 0 ? std::sqrt(thrust_fraction) * hover_command(v, world) : 0.0;
  ic.rotor_speed_rad_s.fill(u * v.rotors[0].input_scaling_rad_s);
  m->reset(ic);
  m->set_motor_commands({{u, u, u, u}, u > 0});
  sensors::Imu imu(with_noise_disabled(v).sensors.imu, world, 1);
  TouchdownMonitor monitor;
  monitor.observe(m->state());
  Touchdown out;
  bool touched = false;
  for (int i = 0; i < 500; ++i) {
    EXPECT_TRUE(m->step().ok());
    const VehicleState& s = m->state();
    monitor.observe(s);
    const auto sample = imu.sample(s, s.time_s);
    touched = touched || s.ground_clearance_m < 0;
    if (!touched) continue;
    out.peak_accel_m_s2 = std::max(out.peak_accel_m_s2, sample.accel_FRD_m_s2.norm());
    out.max_axis_m_s2 = std::max(out.max_axis_m_s2, sample.accel_FRD_m_s2.cwiseAbs().maxCoeff());
    out.rebound_m = std::max(out.rebound_m, s.ground_clearance_m);
    out.deepest_m = std::min(out.deepest_m, s.ground_clearance_m);
  }
  out.rest_clearance_m = m->state().ground_clearance_m;
  out.saturated = imu.saturation().accel + imu.saturation().gyro;
  out.touchdowns = monitor.stats().touchdowns;
  return out;
}

TEST(Touchdown, EverySampleInRangeNoSinkNoRebound) {
  const double full_scale_m_s2 = x500_vehicle_config().sensors.imu.accel_range_m_s2;
  const double static_clearance_m = make()->state().ground_clearance_m;  // legs under the static load
  for (double speed : {0.3, 0.5, 0.7, 1.0, 1.5})
    for (double tilt : {0.0, 10.0, 20.0})
      for (double thrust : {0.0, 0.6}) {
        // Thrust held on a tilted vehicle with nothing levelling it tips it over (a crash, not a
        // touchdown): tilted touchdowns are flown with the motors stopped.
        if (tilt > 0 && thrust > 0) continue;
        const Touchdown t = touch_down(speed, tilt, thrust);
        SCOPED_TRACE(testing::Message() << speed << " m/s, " << tilt << " deg, thrust " << thrust);
        std::printf("%.1f m/s %4.0f deg thrust %.1f: peak %5.2f g (axis %5.2f g), rebound %5.1f mm, deepest %5.1f mm, rest %5.1f mm, %llu touchdowns\n",
                    speed, tilt, thrust, t.peak_accel_m_s2 / kG, t.max_axis_m_s2 / kG, t.rebound_m * 1000, t.deepest_m * 1000,
                    t.rest_clearance_m * 1000, static_cast<unsigned long long>(t.touchdowns));
        EXPECT_EQ(t.saturated, 0u);
        EXPECT_LT(t.max_axis_m_s2, 0.75 * full_scale_m_s2);
        EXPECT_LE(t.rebound_m, 0.01);
        EXPECT_GT(t.deepest_m, -0.05);  // one leg takes a tilted touchdown; the frame never reaches the ground
        EXPECT_NEAR(t.rest_clearance_m, static_clearance_m * (1.0 - thrust), 0.003);
        EXPECT_LE(t.touchdowns, 1u);
      }
}

TEST(Touchdown, PeakAccelerationsAsDocumented) {
  // docs/engine.md states these (level, motors stopped, noise-free IMU at 250 Hz).
  for (const auto& [speed, peak_g] : {std::pair{0.5, 3.8}, std::pair{0.7, 5.0}, std::pair{1.0, 6.6}}) {
    const Touchdown t = touch_down(speed, 0.0, 0.0);
    std::printf("touchdown %.1f m/s: peak %.2f g, compression %.1f mm\n", speed, t.peak_accel_m_s2 / kG, -t.deepest_m * 1000);
    EXPECT_NEAR(t.peak_accel_m_s2 / kG, peak_g, 0.3) << speed << " m/s";
  }
}

TEST(Touchdown, UpsideDownRestsOnTheFrameEvenAtFullThrust) {
  auto m = make();
  const VehicleConfig& v = m->vehicle_config();
  InitialCondition ic;
  ic.q_FLU_to_ENU = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()));
  const double top_m = v.landing_gear.frame_points_FLU_m[0].z();
  ic.p_ENU_m = {0, 0, top_m + 0.002};
  m->reset(ic);
  for (int i = 0; i < 750; ++i) ASSERT_TRUE(m->step().ok());  // 3 s at rest on its back
  EXPECT_NEAR(m->state().p_ENU_m.z(), top_m, 0.005);
  EXPECT_TRUE(m->state().on_ground);
  m->set_motor_commands({{1, 1, 1, 1}, true});  // the rotors push it into the ground
  for (int i = 0; i < 750; ++i) ASSERT_TRUE(m->step().ok());
  EXPECT_GT(m->state().p_ENU_m.z(), top_m - 0.01);
  EXPECT_LT(m->state().p_ENU_m.head<2>().norm(), 0.05);
  m->set_motor_commands({{0, 0, 0, 0}, false});
  m->set_external_force_ENU_N({0, 0, 40.0});  // and a hand can lift it off
  for (int i = 0; i < 250; ++i) ASSERT_TRUE(m->step().ok());
  EXPECT_GT(m->state().p_ENU_m.z(), top_m + 0.5);
}

TEST(Touchdown, OnItsSideRestsOnLegAndFrame) {
  auto m = make();
  InitialCondition ic;
  ic.q_FLU_to_ENU = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  ic.p_ENU_m = {0, 0, 0.3};
  m->reset(ic);
  for (int i = 0; i < 1250; ++i) ASSERT_TRUE(m->step().ok());
  EXPECT_GT(m->state().ground_clearance_m, -0.01);
  EXPECT_LT(m->state().v_ENU_m_s.norm(), 0.01);
}

TEST(Touchdown, ImuReadsTheStepMeanOverSubsteps) {
  // Differential thrust: the roll rate grows steadily; with 4 sub-steps the gyro's mean lies between
  // the rate one step back and the rate now (one sub-step: the rate at the step's end).
  for (double substep_s : {0.004, 0.001}) {
    WorldConfig w = default_world_config();
    w.physics.max_substep_s = substep_s;
    auto m = make(w);
    InitialCondition ic;
    ic.p_ENU_m = {0, 0, 10};
    ic.rotor_speed_rad_s.fill(700);
    m->reset(ic);
    m->set_motor_commands({{0.8, 0.6, 0.6, 0.8}, true});
    for (int i = 0; i < 20; ++i) ASSERT_TRUE(m->step().ok());
    const double before = m->state().w_FLU_rad_s.x();
    ASSERT_TRUE(m->step().ok());
    const double after = m->state().w_FLU_rad_s.x();
    const double mean = m->state().w_step_mean_FLU_rad_s.x();
    ASSERT_GT(std::abs(after - before), 1e-3);
    if (substep_s == 0.004) {
      EXPECT_DOUBLE_EQ(mean, after);
    } else {
      EXPECT_GT(std::abs(mean - before), 0.1 * std::abs(after - before));
      EXPECT_LT(std::abs(mean - before), 0.9 * std::abs(after - before));
    }
  }
}

TEST(Touchdown, SubstepsGiveTheSameTouchdown) {
  WorldConfig w = default_world_config();
  w.physics.max_substep_s = 0.001;
  const Touchdown coarse = touch_down(0.7, 0.0, 0.0);
  const Touchdown fine = touch_down(0.7, 0.0, 0.0, w);
  EXPECT_NEAR(fine.peak_accel_m_s2, coarse.peak_accel_m_s2, 0.15 * coarse.peak_accel_m_s2);
  EXPECT_LE(fine.rebound_m, 0.01);
}

}  // namespace
}  // namespace hitl::model

namespace hitl::sensors {
namespace {

TEST(ImuRange, SamplesClipAtFullScaleAndAreCounted) {
  model::ImuConfig c = model::with_noise_disabled(model::x500_vehicle_config()).sensors.imu;
  Imu imu(c, model::default_world_config(), 1);
  model::VehicleState s;
  s.specific_force_FLU_m_s2 = {0, 0, 20 * 9.80665};  // 20 g up: beyond +-16 g
  s.w_step_mean_FLU_rad_s = {50, 0, 0};              // beyond 2000 deg/s
  const auto a = imu.sample(s, 0.004);
  EXPECT_NEAR(a.accel_FRD_m_s2.z(), -16 * 9.80665 * 32767.0 / 32768.0, 1e-9);
  EXPECT_NEAR(a.gyro_FRD_rad_s.x(), 2000 * M_PI / 180 * 32767.0 / 32768.0, 1e-9);
  EXPECT_EQ(imu.saturation().accel, 1u);
  EXPECT_EQ(imu.saturation().gyro, 1u);
  s.specific_force_FLU_m_s2 = {0, 0, 9.80665};
  s.w_step_mean_FLU_rad_s = {1, 0, 0};
  const auto b = imu.sample(s, 0.008);
  EXPECT_NEAR(b.accel_FRD_m_s2.z(), -9.80665, 1e-9);
  EXPECT_EQ(imu.saturation().accel, 1u);
  EXPECT_EQ(imu.saturation().gyro, 1u);
}

}  // namespace
}  // namespace hitl::sensors
