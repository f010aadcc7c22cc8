// Sensor models from hand-built states: frames, units, exact values without noise, noise statistics.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "engine/frames/frames.h"
#include "engine/model/atmosphere.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/ground_truth.h"
#include "engine/sensors/sensor_suite.h"
#include "tests/support/statistics.h"

namespace hitl::sensors {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.80665;

model::VehicleState at_rest(const Eigen::Quaterniond& q_FLU_to_ENU = Eigen::Quaterniond::Identity()) {
  model::VehicleState s;
  s.q_FLU_to_ENU = q_FLU_to_ENU;
  s.specific_force_FLU_m_s2 = q_FLU_to_ENU.conjugate() * Eigen::Vector3d(0, 0, kG);
  return s;
}

model::VehicleConfig noiseless() { return model::with_noise_disabled(model::x500_vehicle_config()); }

using test::sample_sigma;

TEST(Imu, LevelAtRestReadsMinusGInFrdExactlyWithoutNoise) {
  Imu imu(noiseless().sensors.imu, model::default_world_config(), 1);
  const ImuSample s = imu.sample(at_rest(), 0.004);
  EXPECT_EQ(s.accel_FRD_m_s2, Eigen::Vector3d(0, 0, -kG));
  EXPECT_EQ(s.gyro_FRD_rad_s, Eigen::Vector3d::Zero());
  // ISA temperature at home (488 m): 15 - 6.5 * 0.488 deg C.
  EXPECT_NEAR(s.temperature_degC, 15.0 - 0.0065 * 488.0, 1e-9);
}

TEST(Imu, NoseUpPitchRateIsPositiveY) {
  Imu imu(noiseless().sensors.imu, model::default_world_config(), 1);
  model::VehicleState s = at_rest();
  s.w_step_mean_FLU_rad_s = {0.0, -0.3, 0.0};  // nose up: about the left (FLU y) axis, negatively
  EXPECT_NEAR(imu.sample(s, 0.004).gyro_FRD_rad_s.y(), 0.3, 1e-15);
  s.w_step_mean_FLU_rad_s = {0.0, 0.0, -0.2};  // turning right (clockwise from above)
  EXPECT_NEAR(imu.sample(s, 0.008).gyro_FRD_rad_s.z(), 0.2, 1e-15);
}

TEST(Imu, LeverArmAddsCentripetalAcceleration) {
  model::ImuConfig config = noiseless().sensors.imu;
  config.position_FLU_m = {0.1, 0.0, 0.0};
  Imu imu(config, model::default_world_config(), 1);
  model::VehicleState s = at_rest();
  s.w_step_mean_FLU_rad_s = {0.0, 0.0, 2.0};  // spinning about z (the step's mean rate, as the IMU reads it)
  const ImuSample out = imu.sample(s, 0.004);
  EXPECT_NEAR(out.accel_FRD_m_s2.x(), -0.1 * 4.0, 1e-12);
  EXPECT_NEAR(out.accel_FRD_m_s2.z(), -kG, 1e-12);
}

TEST(Magnetometer, EarthFieldFromDeclinationInclinationStrength) {
  const model::MagneticFieldConfig f{0.0, 60.0, 0.5};
  const Eigen::Vector3d b = earth_field_NED_gauss(f);
  EXPECT_NEAR(b.x(), 0.25, 1e-12);  // north: F cos(I)
  EXPECT_NEAR(b.y(), 0.0, 1e-12);
  EXPECT_NEAR(b.z(), 0.5 * std::sin(60.0 * kPi / 180), 1e-12);  // down, northern hemisphere
  EXPECT_NEAR(earth_field_NED_gauss({90.0, 0.0, 0.5}).y(), 0.5, 1e-12);  // declination turns it east
}

TEST(Magnetometer, YawedEastReadsTheFieldRotated) {
  const model::WorldConfig world = model::default_world_config();
  Magnetometer mag(noiseless().sensors.mag, world.magnetic_field, 1);
  const Eigen::Vector3d b_NED = earth_field_NED_gauss(world.magnetic_field);
  // Nose north: body FRD = NED.
  const Eigen::Quaterniond north(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()));
  EXPECT_LT((mag.sample(at_rest(north), 0.02).mag_FRD_gauss - b_NED).norm(), 1e-12);
  // Nose east (FLU = ENU): forward = east, right = south, down = down.
  const Eigen::Vector3d east = mag.sample(at_rest(), 0.04).mag_FRD_gauss;
  EXPECT_NEAR(east.x(), b_NED.y(), 1e-12);
  EXPECT_NEAR(east.y(), -b_NED.x(), 1e-12);
  EXPECT_NEAR(east.z(), b_NED.z(), 1e-12);
  EXPECT_NEAR(east.norm(), world.magnetic_field.strength_gauss, 1e-12);
}

TEST(GroundTruth, OdometryQuaternionAndNedPosition) {
  const LocalGeodesy geodesy(model::default_world_config().home);
  model::VehicleState s = at_rest();  // nose east
  s.p_ENU_m = {1.0, 2.0, 3.0};
  s.v_ENU_m_s = {4.0, 0.0, 0.0};  // flying east = forward
  const GroundTruth t = ground_truth(s, geodesy);
  EXPECT_EQ(t.p_NED_m, Eigen::Vector3d(2.0, 1.0, -3.0));
  EXPECT_NEAR(t.q_FRD_to_NED.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(t.q_FRD_to_NED.z(), std::sqrt(0.5), 1e-12);
  EXPECT_LT((t.v_NED_m_s - Eigen::Vector3d(0.0, 4.0, 0.0)).norm(), 1e-12);
  EXPECT_LT((t.v_FRD_m_s - Eigen::Vector3d(4.0, 0.0, 0.0)).norm(), 1e-12);
  EXPECT_LT((t.accel_FRD_m_s2 - Eigen::Vector3d(0, 0, -kG)).norm(), 1e-12);
}

TEST(Geodesy, NorthRaisesLatitudeEastRaisesLongitudeUpRaisesAltitude) {
  const model::HomeConfig home = model::default_world_config().home;
  const LocalGeodesy geodesy(home);
  const Geodetic origin = geodesy.to_geodetic(Eigen::Vector3d::Zero());
  EXPECT_NEAR(origin.lat_deg, home.lat_deg, 1e-12);
  EXPECT_NEAR(origin.lon_deg, home.lon_deg, 1e-12);
  EXPECT_NEAR(origin.alt_m, home.alt_m, 1e-9);
  const Geodetic north = geodesy.to_geodetic({0.0, 100.0, 0.0});
  EXPECT_NEAR(north.lat_deg - home.lat_deg, 100.0 / 111200.0, 0.01 * 100.0 / 111200.0);  // ~111.2 km per degree
  EXPECT_NEAR(north.lon_deg, home.lon_deg, 1e-9);
  const Geodetic east = geodesy.to_geodetic({100.0, 0.0, 0.0});
  EXPECT_GT(east.lon_deg, home.lon_deg);
  EXPECT_NEAR((east.lon_deg - home.lon_deg) * 111320.0 * std::cos(home.lat_deg * kPi / 180), 100.0, 1.0);
  EXPECT_NEAR(geodesy.to_geodetic({0.0, 0.0, 10.0}).alt_m, home.alt_m + 10.0, 1e-3);
  EXPECT_LT((geodesy.to_local_ENU_m(north) - Eigen::Vector3d(0.0, 100.0, 0.0)).norm(), 1e-6);
}

TEST(Barometer, IsaPressureAtAltitudeExactlyWithoutNoise) {
  const model::WorldConfig world = model::default_world_config();
  Barometer baro(noiseless().sensors.baro, world, 1);
  model::VehicleState s = at_rest();
  const BaroSample ground = baro.sample(s, 0.1);
  EXPECT_NEAR(ground.pressure_Pa, 101325.0 * std::pow(1.0 - 2.25577e-5 * 488.0, 5.25588), 0.05);
  EXPECT_NEAR(ground.pressure_alt_m, 488.0, 1e-6);
  EXPECT_NEAR(ground.temperature_degC, 15.0 - 0.0065 * 488.0, 1e-9);
  s.p_ENU_m.z() = 10.0;
  const BaroSample up = baro.sample(s, 0.2);
  EXPECT_NEAR(ground.pressure_Pa - up.pressure_Pa, 10.0 * 11.5, 5.0);  // ~11.5 Pa/m at 500 m
  EXPECT_NEAR(up.pressure_alt_m, 498.0, 1e-6);
}

TEST(Gps, ExactWithoutNoise) {
  const model::WorldConfig world = model::default_world_config();
  Gps gps(noiseless().sensors.gps, world.home, 1);
  model::VehicleState s = at_rest();
  s.p_ENU_m = {0.0, 50.0, 20.0};
  s.v_ENU_m_s = {3.0, 4.0, -1.0};  // towards east-north-east, sinking
  const GpsSample g = gps.sample(s, 1.0);
  const LocalGeodesy geodesy(world.home);
  const Geodetic truth = geodesy.to_geodetic(s.p_ENU_m);
  EXPECT_EQ(g.lat_deg, truth.lat_deg);
  EXPECT_EQ(g.lon_deg, truth.lon_deg);
  EXPECT_EQ(g.alt_m, truth.alt_m);
  EXPECT_GT(g.lat_deg, world.home.lat_deg);
  EXPECT_EQ(g.v_NED_m_s, Eigen::Vector3d(4.0, 3.0, 1.0));
  EXPECT_NEAR(g.ground_speed_m_s, 5.0, 1e-12);
  EXPECT_NEAR(g.course_over_ground_deg, std::atan2(3.0, 4.0) * 180 / kPi, 1e-12);
  EXPECT_EQ(g.fix_type, 3);
  EXPECT_EQ(g.satellites, 10);
  EXPECT_EQ(g.eph_m, 0.9);
  s.v_ENU_m_s = {-1.0, 0.0, 0.0};  // west
  EXPECT_NEAR(gps.sample(s, 1.1).course_over_ground_deg, 270.0, 1e-12);
}

TEST(Gps, DelayReportsOlderFixes) {
  model::GpsConfig config = noiseless().sensors.gps;
  config.delay_s = 0.2;
  Gps gps(config, model::default_world_config().home, 1);
  model::VehicleState s = at_rest();
  for (int k = 0; k <= 60; ++k) {
    const double t = k / 30.0;
    s.p_ENU_m.y() = t;  // moving north at 1 m/s
    const GpsSample g = gps.sample(s, t);
    if (t >= 0.2) {
      EXPECT_LE(g.time_s, t - 0.2 + 1e-9);
      EXPECT_GT(g.time_s, t - 0.2 - 1.0 / 30.0);
    }
  }
}

TEST(Gps, WanderingErrorHasItsSigmaAndVelocityNoiseItsSigma) {
  model::GpsConfig config = model::x500_vehicle_config().sensors.gps;
  config.horizontal_noise_m = config.vertical_noise_m = 0.0;
  config.error_correlation_time_s = 1.0;  // short, to see many independent values
  Gps gps(config, model::default_world_config().home, 5);
  const model::VehicleState s = at_rest();
  std::vector<double> east, vn;
  for (int k = 1; k <= 30 * 600; ++k) {
    const GpsSample g = gps.sample(s, k / 30.0);
    east.push_back(gps.position_error_ENU_m().x());
    vn.push_back(g.v_NED_m_s.x());
  }
  EXPECT_NEAR(sample_sigma(east), config.horizontal_error_sigma_m, 0.1 * config.horizontal_error_sigma_m);
  EXPECT_NEAR(sample_sigma(vn), config.velocity_noise_m_s, 0.05 * config.velocity_noise_m_s);
}

/// Samples an inertial sensor of `config` for 60 s at its rate; returns per-axis sample sigmas.
template <class Sample>
Eigen::Vector3d sigmas_over_60_s(double rate_hz, Sample sample) {
  std::vector<double> axes[3];
  const int n = static_cast<int>(60.0 * rate_hz);
  for (int k = 1; k <= n; ++k) {
    const Eigen::Vector3d v = sample(k / rate_hz);
    for (int i = 0; i < 3; ++i) axes[i].push_back(v[i]);
  }
  return {sample_sigma(axes[0]), sample_sigma(axes[1]), sample_sigma(axes[2])};
}

TEST(SensorNoise, ImuSigmaIsDensityTimesSqrtRate) {
  model::ImuConfig config = model::x500_vehicle_config().sensors.imu;
  for (model::InertialNoiseConfig* n : {&config.accel, &config.gyro}) n->random_walk = n->turn_on_bias_sigma = 0.0;
  Imu imu(config, model::default_world_config(), 11);
  const model::VehicleState s = at_rest();
  std::vector<ImuSample> samples;
  const Eigen::Vector3d accel = sigmas_over_60_s(config.rate_hz, [&](double t) {
    samples.push_back(imu.sample(s, t));
    return samples.back().accel_FRD_m_s2;
  });
  std::size_t i = 0;
  const Eigen::Vector3d gyro = sigmas_over_60_s(config.rate_hz, [&](double) { return samples[i++].gyro_FRD_rad_s; });
  const double accel_expected = config.accel.noise_density * std::sqrt(config.rate_hz);  // 0.063 m/s^2
  const double gyro_expected = config.gyro.noise_density * std::sqrt(config.rate_hz);    // 0.0054 rad/s
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(accel[a], accel_expected, 0.05 * accel_expected) << "axis " << a;
    EXPECT_NEAR(gyro[a], gyro_expected, 0.05 * gyro_expected) << "axis " << a;
  }
}

TEST(SensorNoise, MagSigmaIsDensityTimesSqrtRate) {
  model::MagConfig config = model::x500_vehicle_config().sensors.mag;
  config.noise.random_walk = 0.0;
  Magnetometer mag(config, model::default_world_config().magnetic_field, 12);
  const model::VehicleState s = at_rest();
  const Eigen::Vector3d sigma = sigmas_over_60_s(config.rate_hz, [&](double t) { return mag.sample(s, t).mag_FRD_gauss; });
  const double expected = config.noise.noise_density * std::sqrt(config.rate_hz);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(sigma[a], expected, 0.05 * expected) << "axis " << a;
}

TEST(SensorNoise, BaroSigmaIsTheConfiguredSigma) {
  const model::BaroConfig config = model::x500_vehicle_config().sensors.baro;
  Barometer baro(config, model::default_world_config(), 13);
  const model::VehicleState s = at_rest();
  std::vector<double> p;
  for (int k = 1; k <= 6000; ++k) p.push_back(baro.sample(s, k / config.rate_hz).pressure_Pa);  // 600 s
  EXPECT_NEAR(sample_sigma(p), config.noise_pa, 0.05 * config.noise_pa);
}

TEST(SensorNoise, DefaultBiasesAreDrawnAndWander) {
  const model::ImuConfig config = model::x500_vehicle_config().sensors.imu;
  Imu imu(config, model::default_world_config(), 21);
  EXPECT_GT(imu.accel_noise().turn_on_bias().norm(), 0.0);
  EXPECT_LT(imu.accel_noise().turn_on_bias().cwiseAbs().maxCoeff(), 5.0 * config.accel.turn_on_bias_sigma);
  const model::VehicleState s = at_rest();
  for (int k = 1; k <= 2500; ++k) imu.sample(s, k / config.rate_hz);
  const Eigen::Vector3d bias = imu.accel_noise().bias();
  EXPECT_GT(bias.norm(), 0.0);
  // After 10 s of random walk at 0.006 m/s^3/sqrt(Hz): of the order of 0.006 * sqrt(10).
  EXPECT_LT(bias.cwiseAbs().maxCoeff(), 5.0 * 0.006 * std::sqrt(10.0));
}

TEST(SensorNoise, EachSensorHasItsOwnStream) {
  // Changing one sensor's noise leaves every other sensor's samples bit-identical.
  model::VehicleConfig other = model::x500_vehicle_config();
  other.sensors.baro.noise_pa = 10.0;
  other.sensors.gps.velocity_noise_m_s = 0.5;
  SensorSuite a(model::x500_vehicle_config(), model::default_world_config(), 99);
  SensorSuite b(other, model::default_world_config(), 99);
  SensorSuite c(model::x500_vehicle_config(), model::default_world_config(), 100);
  model::VehicleState s = at_rest();
  bool seed_matters = false;
  for (int k = 1; k <= 500; ++k) {
    s.time_s = k * 0.004;
    const SensorFrame fa = a.sample_due(s), fb = b.sample_due(s), fc = c.sample_due(s);
    ASSERT_TRUE(fa.imu && fb.imu);
    EXPECT_EQ(fa.imu->accel_FRD_m_s2, fb.imu->accel_FRD_m_s2);
    EXPECT_EQ(fa.imu->gyro_FRD_rad_s, fb.imu->gyro_FRD_rad_s);
    if (fa.mag) {
      EXPECT_EQ(fa.mag->mag_FRD_gauss, fb.mag->mag_FRD_gauss);
    }
    seed_matters = seed_matters || fa.imu->accel_FRD_m_s2 != fc.imu->accel_FRD_m_s2;
  }
  EXPECT_TRUE(seed_matters);
}

TEST(SensorNoise, ResetRepeatsTheSamples) {
  SensorSuite suite(model::x500_vehicle_config(), model::default_world_config(), 3);
  model::VehicleState s = at_rest();
  std::vector<Eigen::Vector3d> first;
  for (int k = 1; k <= 50; ++k) {
    s.time_s = k * 0.004;
    first.push_back(suite.sample_due(s).imu->accel_FRD_m_s2);
  }
  suite.reset();
  for (int k = 1; k <= 50; ++k) {
    s.time_s = k * 0.004;
    EXPECT_EQ(suite.sample_due(s).imu->accel_FRD_m_s2, first[k - 1]);
  }
}

}  // namespace
}  // namespace hitl::sensors
