// The environment and vehicle faults in the model (engine/faults: wind, gust, turbulence,
// payload): a wind event moves the air the model flies in; a payload's weight sinks a hover by
// the acceleration m_payload g / M its closed form gives.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/model/motor_model.h"
#include "engine/model/multicopter.h"
#include "engine/model/wind.h"
#include "engine/model/x500_defaults.h"

namespace hitl::model {
namespace {

std::unique_ptr<Multicopter> hovering_at(double altitude_m) {
  const VehicleConfig v = x500_vehicle_config();
  const WorldConfig w = default_world_config();
  auto created = Multicopter::create(v, w, 1);
  EXPECT_TRUE(created) << created.error().message;
  auto m = std::move(created.value());
  const double u_h = hover_command(v, w);
  InitialCondition ic;
  ic.p_ENU_m = {0, 0, altitude_m};
  ic.rotor_speed_rad_s.fill(u_h * v.rotors[0].input_scaling_rad_s);
  m->reset(ic);
  m->set_motor_commands({{u_h, u_h, u_h, u_h}, true});
  return m;
}

TEST(FaultEvents, AWindEventAddsToTheWorldsWindAndTurbulenceHasItsSigma) {
  WindConfig config;
  config.velocity_ENU_m_s = {1, 0, 0};
  Wind wind(config, 7);
  wind.set_event({0, 3, 0}, 0, 0);
  EXPECT_TRUE(wind.advance(0.004).isApprox(Eigen::Vector3d(1, 3, 0)));
  wind.set_event({0, 0, 0}, 2.0, 0.5);  // 2 m/s sigma, 0.5 s correlation
  double sum2 = 0;
  const int n = 250 * 400;
  for (int i = 0; i < n; ++i) sum2 += (wind.advance(0.004) - Eigen::Vector3d(1, 0, 0)).squaredNorm();
  EXPECT_NEAR(std::sqrt(sum2 / (3.0 * n)), 2.0, 0.2);  // 400 s: 800 correlation times
  wind.set_event({0, 0, 0}, 0, 0);
  EXPECT_TRUE(wind.advance(0.004).isApprox(Eigen::Vector3d(1, 0, 0)));  // over: the world's wind alone
}

TEST(FaultEvents, TheModelFliesInTheWindEvent) {
  auto m = hovering_at(10);
  m->set_wind_event({4, 0, 0}, 0, 0);  // 4 m/s towards east
  for (int i = 0; i < 250; ++i) ASSERT_TRUE(m->step());
  EXPECT_TRUE(m->state().wind_ENU_m_s.isApprox(Eigen::Vector3d(4, 0, 0)));
  EXPECT_GT(m->state().v_ENU_m_s.x(), 0.1);  // dragged downwind
}

TEST(FaultEvents, APayloadsWeightSinksAHoverByItsShareOfTheMass) {
  auto plain = hovering_at(10), loaded = hovering_at(10);
  const double payload_kg = 0.5;
  const WorldConfig w = default_world_config();
  loaded->set_external_force_ENU_N({0, 0, -payload_kg * w.gravity_m_s2});  // what the session sets for payload:0.5
  for (int i = 0; i < 50; ++i) {  // 0.2 s
    ASSERT_TRUE(plain->step());
    ASSERT_TRUE(loaded->step());
  }
  const double dv_m_s = loaded->state().v_ENU_m_s.z() - plain->state().v_ENU_m_s.z();
  const double expected_m_s = -payload_kg * w.gravity_m_s2 / total_mass_kg(x500_vehicle_config()) * 0.2;
  EXPECT_NEAR(dv_m_s, expected_m_s, 0.05 * std::abs(expected_m_s));
}

}  // namespace
}  // namespace hitl::model
