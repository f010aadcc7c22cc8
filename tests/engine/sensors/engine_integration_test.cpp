// Physics and sensors together, as the session loop will drive them: step, then sample what is due.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/model/multicopter.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/sensor_suite.h"

namespace hitl {
namespace {

using model::Multicopter;

struct Sim {
  explicit Sim(const model::VehicleConfig& vehicle = model::x500_vehicle_config(), std::uint64_t seed = 1)
      : plant(std::move(Multicopter::create(vehicle, model::default_world_config(), seed).value())),
        sensors(vehicle, model::default_world_config(), seed) {}
  sensors::SensorFrame step() {
    EXPECT_TRUE(plant->step().ok());
    return sensors.sample_due(plant->state());
  }
  std::unique_ptr<Multicopter> plant;
  sensors::SensorSuite sensors;
};

TEST(Engine, AtRestAltitudeAndPressureConstantAccelMinusG) {
  Sim sim(model::with_noise_disabled(model::x500_vehicle_config()));
  const double alt0 = sim.step().truth.alt_m;
  double p0 = -1.0;
  for (int i = 0; i < 2500; ++i) {  // 10 s
    const sensors::SensorFrame f = sim.step();
    ASSERT_NEAR(f.truth.alt_m, alt0, 1e-3);
    ASSERT_TRUE(f.imu);
    ASSERT_NEAR(f.imu->accel_FRD_m_s2.z(), -9.80665, 1e-6);
    ASSERT_NEAR(f.imu->accel_FRD_m_s2.head<2>().norm(), 0.0, 1e-6);
    if (f.baro) {
      if (p0 < 0) p0 = f.baro->pressure_Pa;
      ASSERT_NEAR(f.baro->pressure_Pa, p0, 0.012);  // 1 mm of altitude
    }
  }
}

TEST(Engine, AtRestWithDefaultNoiseAccelIsMinusGPlusNoise) {
  Sim sim;
  const Eigen::Vector3d turn_on = sim.sensors.imu().accel_noise().turn_on_bias();
  std::vector<double> z;
  for (int i = 0; i < 2500; ++i) z.push_back(sim.step().imu->accel_FRD_m_s2.z());
  double mean = 0.0;
  for (double v : z) mean += v;
  mean /= static_cast<double>(z.size());
  double var = 0.0;
  for (double v : z) var += (v - mean) * (v - mean);
  const double sigma = std::sqrt(var / static_cast<double>(z.size() - 1));
  // -g + turn-on bias, within the bias random walk over 10 s (~0.02) and the mean's noise.
  EXPECT_NEAR(mean, -9.80665 + turn_on.z(), 0.06);
  const double white = 0.004 * std::sqrt(250.0);
  EXPECT_GT(sigma, 0.9 * white);
  EXPECT_LT(sigma, 1.3 * white);
}

TEST(Engine, FacingEastMagAndOdometryQuaternion) {
  // The vehicle starts with FLU = ENU (Gazebo's default spawn): nose east, heading 90 deg.
  Sim sim(model::with_noise_disabled(model::x500_vehicle_config()));
  sensors::SensorFrame f;
  while (!f.mag) f = sim.step();
  const Eigen::Vector3d b_NED = sensors::earth_field_NED_gauss(model::default_world_config().magnetic_field);
  EXPECT_NEAR(f.mag->mag_FRD_gauss.x(), b_NED.y(), 1e-6);
  EXPECT_NEAR(f.mag->mag_FRD_gauss.y(), -b_NED.x(), 1e-6);
  EXPECT_NEAR(f.mag->mag_FRD_gauss.z(), b_NED.z(), 1e-6);
  EXPECT_NEAR(f.truth.q_FRD_to_NED.w(), std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(f.truth.q_FRD_to_NED.z(), std::sqrt(0.5), 1e-6);
}

TEST(Engine, ClimbShowsInBaroGpsAndTruth) {
  Sim sim(model::with_noise_disabled(model::x500_vehicle_config()));
  sensors::SensorFrame first = sim.step();
  while (!first.baro || !first.gps) first = sim.step();
  sim.plant->set_motor_commands({{0.85, 0.85, 0.85, 0.85}, true});
  sensors::SensorFrame last;
  double last_pressure = first.baro->pressure_Pa, last_alt = first.gps->alt_m;
  for (int i = 0; i < 750; ++i) {  // 3 s
    last = sim.step();
    if (last.baro) last_pressure = last.baro->pressure_Pa;
    if (last.gps) last_alt = last.gps->alt_m;
  }
  const double climbed_m = -last.truth.p_NED_m.z() + first.truth.p_NED_m.z();
  EXPECT_GT(climbed_m, 2.0);
  EXPECT_NEAR(last_alt - first.gps->alt_m, climbed_m, 0.5);  // GPS sampled up to 1/30 s earlier
  EXPECT_LT(last_pressure, first.baro->pressure_Pa - 10.0 * climbed_m);
  EXPECT_LT(last.truth.v_NED_m_s.z(), -0.5);  // climbing: NED velocity down is negative
}

TEST(Engine, SameSeedSameSamples) {
  Sim a(model::x500_vehicle_config(), 8), b(model::x500_vehicle_config(), 8);
  for (int i = 0; i < 500; ++i) {
    a.plant->set_motor_commands({{0.8, 0.8, 0.8, 0.8}, true});
    b.plant->set_motor_commands({{0.8, 0.8, 0.8, 0.8}, true});
    const sensors::SensorFrame fa = a.step(), fb = b.step();
    ASSERT_EQ(fa.imu->accel_FRD_m_s2, fb.imu->accel_FRD_m_s2);
    ASSERT_EQ(fa.truth.p_NED_m, fb.truth.p_NED_m);
    ASSERT_EQ(fa.gps.has_value(), fb.gps.has_value());
    if (fa.gps) {
      ASSERT_EQ(fa.gps->lat_deg, fb.gps->lat_deg);
    }
  }
}

}  // namespace
}  // namespace hitl
