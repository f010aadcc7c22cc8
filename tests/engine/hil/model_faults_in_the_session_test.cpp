// The vehicle and environment faults through the session (docs/faults.md: motor, prop-damage,
// payload, wind, gust, turbulence), as a board reads them off HIL_SENSOR and HIL_GPS. A stand-in
// board climbs at 0.9 on every motor in lockstep, noise off; each fault starts at 0.5 s and is
// measured against the same flight without it (same steps, same answers: the difference is the fault).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/frames/frames.h"
#include "tests/engine/hil/lockstep_board.h"

namespace hitl::hil {
namespace {

namespace msg = mavlink::msg;
using test_lockstep::mean_over;
using test_lockstep::Seen;

constexpr double kStart_s = 0.5;
constexpr double kStep_s = 0.004;

Seen climb(const std::vector<std::string>& faults, uint64_t seed = 1) {
  return test_lockstep::fly(faults, 1.5, [](uint64_t) { return 0.9; }, false, seed);
}

Eigen::Vector3d accel_FRD_m_s2(const msg::HilSensor& s) { return {s.xacc, s.yacc, s.zacc}; }
Eigen::Vector3d gyro_FRD_rad_s(const msg::HilSensor& s) { return {s.xgyro, s.ygyro, s.zgyro}; }
/// HIL_GPS's velocity, NED m/s, the last one before `t_s`.
Eigen::Vector3d v_NED_m_s(const Seen& seen, double t_s) {
  auto it = seen.gps.lower_bound(static_cast<uint64_t>(t_s * 1e6));
  EXPECT_NE(it, seen.gps.begin());
  --it;
  return Eigen::Vector3d(it->second.vn, it->second.ve, it->second.vd) * 0.01;
}
/// The sample at `t_s` of the faulted flight less the same sample without the fault.
Eigen::Vector3d accel_difference(const Seen& with, const Seen& without, double t_s) {
  const auto t_us = static_cast<uint64_t>(std::llround(t_s * 1e6));
  EXPECT_TRUE(with.sensors.count(t_us) && without.sensors.count(t_us)) << t_s;
  if (!with.sensors.count(t_us) || !without.sensors.count(t_us)) return Eigen::Vector3d::Zero();
  return accel_FRD_m_s2(with.sensors.at(t_us)) - accel_FRD_m_s2(without.sensors.at(t_us));
}
/// The HIL_SENSOR of the step at `t_s`.
const msg::HilSensor& sensor_at(const Seen& seen, double t_s) { return seen.sensors.at(static_cast<uint64_t>(std::llround(t_s * 1e6))); }
double total_mass_kg() { return model::total_mass_kg(model::x500_vehicle_config()); }

// motor:0,0 (front-right out): a quarter of the lift is gone at once, and the others' unbalanced
// moments roll right, pitch down and yaw left at the angular accelerations the geometry implies.
TEST(ModelFaultsInTheSession, MotorOutLosesItsLiftAndTurnsAsTheGeometryImplies) {
  const auto healthy = climb({}), out = climb({"motor:0,0@0.5"});
  const double t_s = kStart_s + 2 * kStep_s;
  const double thrust_N = -accel_FRD_m_s2(sensor_at(healthy, t_s)).z() * total_mass_kg() / 4;
  EXPECT_NEAR(accel_difference(out, healthy, t_s).z(), thrust_N / total_mass_kg(), 0.05 * thrust_N / total_mass_kg())
      << "a quarter of the lift gone";
  // The closed form (tests/engine/model/motor_fault_test.cpp): motor 0's moment about the centre,
  // lost; over the inertia about the base origin.
  const auto v = model::x500_vehicle_config();
  const Eigen::Vector3d r0 = v.rotors[0].position_FLU_m;
  const Eigen::Vector3d left_FLU_Nm = -Eigen::Vector3d(r0.y() * thrust_N, -r0.x() * thrust_N, -v.rotors[0].moment_constant_m * thrust_N);
  Eigen::Vector3d inertia_kgm2 = v.base.inertia_kgm2;
  for (const auto& r : v.rotors) {
    const Eigen::Vector3d p = r.position_FLU_m;
    inertia_kgm2 += r.inertia_kgm2 + r.mass_kg * Eigen::Vector3d(p.y() * p.y() + p.z() * p.z(), p.x() * p.x() + p.z() * p.z(),
                                                                  p.x() * p.x() + p.y() * p.y());
  }
  const Eigen::Vector3d expected_FRD_rad_s2 = frames::flu_to_frd(Eigen::Vector3d(left_FLU_Nm.cwiseQuotient(inertia_kgm2)));
  // The gyro's slope over the first 40 ms (the healthy climb does not turn).
  const auto at = [&](double s) { return gyro_FRD_rad_s(sensor_at(out, s)); };
  const Eigen::Vector3d alpha_FRD_rad_s2 = (at(kStart_s + 11 * kStep_s) - at(kStart_s + kStep_s)) / (10 * kStep_s);
  std::printf("motor 0 out: angular acceleration FRD %.1f %.1f %.1f rad/s^2 (closed form %.1f %.1f %.1f)\n", alpha_FRD_rad_s2.x(),
              alpha_FRD_rad_s2.y(), alpha_FRD_rad_s2.z(), expected_FRD_rad_s2.x(), expected_FRD_rad_s2.y(), expected_FRD_rad_s2.z());
  EXPECT_GT(expected_FRD_rad_s2.x(), 0);  // right side down
  EXPECT_LT(expected_FRD_rad_s2.y(), 0);  // nose down
  EXPECT_LT(expected_FRD_rad_s2.z(), 0);  // heading decreasing
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(alpha_FRD_rad_s2[i], expected_FRD_rad_s2[i], 0.15 * std::abs(expected_FRD_rad_s2[i])) << i;
  EXPECT_LT(mean_over(healthy.sensors, 0.1, 1.5, [](const msg::HilSensor& s) { return gyro_FRD_rad_s(s).norm(); }), 1e-6);
}

// prop-damage:1,0.7,4: motor 1 at 70 % (its lost 30 % of the lift) and its imbalance, 4 m/s^2
// rotating in the IMU's x-y plane once per revolution.
TEST(ModelFaultsInTheSession, PropDamageLosesThrustAndShakesTheImuAtItsAmplitude) {
  const auto healthy = climb({}), damaged = climb({"prop-damage:1,0.7,4@0.5"});
  const double t_s = kStart_s + 2 * kStep_s;
  const double thrust_N = -accel_FRD_m_s2(sensor_at(healthy, t_s)).z() * total_mass_kg() / 4;
  EXPECT_NEAR(accel_difference(damaged, healthy, t_s).z(), 0.3 * thrust_N / total_mass_kg(), 0.02 * thrust_N / total_mass_kg());
  for (int k = 1; k <= 5; ++k) {
    const Eigen::Vector3d d = accel_difference(damaged, healthy, kStart_s + k * kStep_s);
    EXPECT_NEAR(d.head<2>().norm(), 4.0, 0.2) << "at step " << k;
  }
  EXPECT_NEAR(accel_difference(damaged, healthy, kStart_s - kStep_s).norm(), 0.0, 1e-6);  // nothing before it
}

// payload:0.5: its weight pulls down at once (the accelerometer reads m g / M less lift), and the
// climb falls behind.
TEST(ModelFaultsInTheSession, PayloadPullsDownByItsWeightOverTheMass) {
  const auto plain = climb({}), loaded = climb({"payload:0.5@0.5"});
  const double expected_m_s2 = 0.5 * model::default_world_config().gravity_m_s2 / total_mass_kg();
  for (int k = 1; k <= 3; ++k)
    EXPECT_NEAR(accel_difference(loaded, plain, kStart_s + k * kStep_s).z(), expected_m_s2, 0.03 * expected_m_s2) << k;
  EXPECT_GT(v_NED_m_s(loaded, 1.5).z() - v_NED_m_s(plain, 1.5).z(), 0.5 * expected_m_s2 * 1.0) << "sinks against the climb";
}

// wind:5,0 and gust:0,5 (1-cosine over 1 s): the rotors' drag carries the vehicle with the air,
// north under the wind, east under the gust and only once it has risen.
TEST(ModelFaultsInTheSession, WindAndGustCarryTheVehicleWithTheAir) {
  const auto calm = climb({}), windy = climb({"wind:5,0@0.5"}), gusty = climb({"gust:0,5@0.5+1"});
  const Eigen::Vector3d calm_v = v_NED_m_s(calm, 1.5);
  EXPECT_NEAR(calm_v.head<2>().norm(), 0.0, 1e-9);
  const Eigen::Vector3d wind_v = v_NED_m_s(windy, 1.5), gust_v = v_NED_m_s(gusty, 1.5), gust_early_v = v_NED_m_s(gusty, 0.6);
  std::printf("at 1.5 s, NED m/s: wind:5,0 %.2f %.2f, gust:0,5 %.2f %.2f (at 0.6 s %.3f)\n", wind_v.x(), wind_v.y(), gust_v.x(),
              gust_v.y(), gust_early_v.y());
  // (Uncontrolled, the vehicle also tilts in the air's drag and turns: mostly, not only, downwind.)
  EXPECT_GT(wind_v.x(), 0.2);
  EXPECT_GT(wind_v.x(), 2 * std::abs(wind_v.y()));
  EXPECT_GT(gust_v.y(), 0.1);
  EXPECT_GT(gust_v.y(), 2 * std::abs(gust_v.x()));
  EXPECT_LT(gust_early_v.y(), 0.05 * gust_v.y()) << "a 1-cosine gust starts gently";
}

// turbulence:3: the air moves at random (seeded), so the vehicle wanders from the calm climb; the
// same seed gives the same flight, another a different one.
TEST(ModelFaultsInTheSession, TurbulenceWandersFromTheCalmClimbAsTheSeedSays) {
  const auto calm = climb({}), a = climb({"turbulence:3@0.5"}), again = climb({"turbulence:3@0.5"}),
             other = climb({"turbulence:3@0.5"}, 2);
  const Eigen::Vector3d d = v_NED_m_s(a, 1.5) - v_NED_m_s(calm, 1.5);
  std::printf("turbulence:3 at 1.5 s: %.2f %.2f %.2f m/s from the calm climb\n", d.x(), d.y(), d.z());
  EXPECT_GT(d.head<2>().norm(), 0.05);
  EXPECT_EQ(v_NED_m_s(a, 1.5), v_NED_m_s(again, 1.5));
  EXPECT_NE(v_NED_m_s(a, 1.5), v_NED_m_s(other, 1.5));
  EXPECT_EQ(v_NED_m_s(a, 0.5), v_NED_m_s(calm, 0.5));  // nothing before it
}

}  // namespace
}  // namespace hitl::hil
