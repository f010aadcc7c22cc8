// The sensor faults on a sampled frame: what a bias, an offset, a lost or jumped GPS does to it.
#include <gtest/gtest.h>

#include "engine/faults/sensor_faults.h"
#include "engine/model/atmosphere.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/gps.h"
#include "engine/sensors/imu.h"

namespace hitl::faults {
namespace {

sensors::SensorFrame frame_with_everything() {
  sensors::SensorFrame f;
  f.imu = sensors::ImuSample{0, {0, 0, -9.81}, {0.01, 0, 0}, 20};
  f.mag = sensors::MagSample{0, {0.2, 0, 0.4}};
  f.baro = sensors::BaroSample{0, 95000, 15, 0};
  f.gps = sensors::GpsSample{};
  f.gps->lat_deg = 47.397742;
  f.gps->lon_deg = 8.545594;
  f.gps->eph_m = 0.9;
  f.gps->satellites = 10;
  return f;
}

TEST(SensorFaults, BiasesAndOffsetsAddToTheReadings) {
  ActiveFaults a;
  a.accel_bias_FRD_m_s2 = {0.5, -0.2, 0.1};
  a.gyro_bias_FRD_rad_s = {0, 0.05, 0};
  a.mag_offset_FRD_gauss = {0.1, 0, 0};
  a.baro_offset_Pa = 120;
  auto f = frame_with_everything();
  const auto atmosphere = model::default_world_config().atmosphere;
  SensorFaults(atmosphere).apply(a, 0, f);
  EXPECT_TRUE(f.imu->accel_FRD_m_s2.isApprox(Eigen::Vector3d(0.5, -0.2, -9.71)));
  EXPECT_TRUE(f.imu->gyro_FRD_rad_s.isApprox(Eigen::Vector3d(0.01, 0.05, 0)));
  EXPECT_TRUE(f.mag->mag_FRD_gauss.isApprox(Eigen::Vector3d(0.3, 0, 0.4)));
  EXPECT_DOUBLE_EQ(f.baro->pressure_Pa, 95120);
  EXPECT_NEAR(f.baro->pressure_alt_m, model::isa_altitude_m(atmosphere, 95120), 1e-9);
  EXPECT_LT(f.baro->pressure_alt_m, model::isa_altitude_m(atmosphere, 95000));  // more pressure reads lower
}

TEST(SensorFaults, GpsLossRemovesTheFixJumpMovesItDegradeReportsWorse) {
  const auto atmosphere = model::default_world_config().atmosphere;
  ActiveFaults loss;
  loss.gps_loss = true;
  auto f = frame_with_everything();
  SensorFaults(atmosphere).apply(loss, 0, f);
  EXPECT_FALSE(f.gps);
  EXPECT_TRUE(f.imu);

  ActiveFaults jump;
  jump.gps_north_m = 100;
  jump.gps_east_m = -50;
  jump.gps_report = GpsReport{2, 4, 5.0, 8.0};
  auto g = frame_with_everything();
  SensorFaults(atmosphere).apply(jump, 0, g);
  // 1 deg of latitude at 47.4 N is 111,180 m; 1 deg of longitude there 75,330 m.
  EXPECT_NEAR((g.gps->lat_deg - 47.397742) * 111180.0, 100.0, 0.5);
  EXPECT_NEAR((g.gps->lon_deg - 8.545594) * 75330.0, -50.0, 0.5);
  EXPECT_EQ(g.gps->fix_type, 2);
  EXPECT_EQ(g.gps->satellites, 4);
  EXPECT_DOUBLE_EQ(g.gps->eph_m, 5.0);
  EXPECT_DOUBLE_EQ(g.gps->epv_m, 8.0);
}

/// A frame whose readings differ from frame_with_everything()'s.
sensors::SensorFrame another_frame() {
  auto f = frame_with_everything();
  f.imu->accel_FRD_m_s2 = {1, 2, -9};
  f.imu->gyro_FRD_rad_s = {0.1, 0.2, 0.3};
  f.mag->mag_FRD_gauss = {0.1, 0.1, 0.5};
  f.baro->pressure_Pa = 94000;
  f.baro->pressure_alt_m = 700;
  return f;
}

TEST(SensorFaults, StuckSensorsRepeatTheLastReadingBeforeTheFaultUntilItEnds) {
  SensorFaults faults(model::default_world_config().atmosphere);
  ActiveFaults none, stuck;
  stuck.imu_stuck = stuck.mag_stuck = stuck.baro_stuck = true;
  auto first = frame_with_everything();
  faults.apply(none, 0.0, first);
  auto second = another_frame();
  faults.apply(stuck, 0.004, second);  // stuck from here: the reading before it, repeated
  EXPECT_EQ(second.imu->accel_FRD_m_s2, first.imu->accel_FRD_m_s2);
  EXPECT_EQ(second.imu->gyro_FRD_rad_s, first.imu->gyro_FRD_rad_s);
  EXPECT_EQ(second.mag->mag_FRD_gauss, first.mag->mag_FRD_gauss);
  EXPECT_EQ(second.baro->pressure_Pa, first.baro->pressure_Pa);
  EXPECT_EQ(second.baro->pressure_alt_m, first.baro->pressure_alt_m);
  EXPECT_EQ(second.baro->temperature_degC, first.baro->temperature_degC);
  auto third = another_frame();
  faults.apply(stuck, 0.008, third);
  EXPECT_EQ(third.imu->accel_FRD_m_s2, first.imu->accel_FRD_m_s2);
  auto fourth = another_frame();
  faults.apply(none, 0.012, fourth);  // ended: live again
  EXPECT_EQ(fourth.imu->accel_FRD_m_s2, Eigen::Vector3d(1, 2, -9));
  EXPECT_EQ(fourth.baro->pressure_Pa, 94000);
}

TEST(SensorFaults, ImuClipHoldsEachAxisWithinTheRange) {
  ActiveFaults a;
  a.imu_clip_accel_m_s2 = 5;
  a.imu_clip_gyro_rad_s = 0.15;
  auto f = another_frame();
  SensorFaults(model::default_world_config().atmosphere).apply(a, 0, f);
  EXPECT_EQ(f.imu->accel_FRD_m_s2, Eigen::Vector3d(1, 2, -5));
  EXPECT_EQ(f.imu->gyro_FRD_rad_s, Eigen::Vector3d(0.1, 0.15, 0.15));
}

TEST(SensorFaults, VibrationIsASinusoidOfItsAmplitudeAndFrequencyFromItsStart) {
  ActiveFaults a;
  a.vibrations.push_back({3.0, 10.0, 1.0});  // 3 m/s^2 at 10 Hz from t = 1 s
  SensorFaults faults(model::default_world_config().atmosphere);
  for (double t : {1.0, 1.025, 1.05, 1.0125}) {
    auto f = frame_with_everything();
    faults.apply(a, t, f);
    const double phase = 2 * M_PI * 10 * (t - 1.0);
    EXPECT_NEAR(f.imu->accel_FRD_m_s2.x(), 3 * std::cos(phase), 1e-9);
    EXPECT_NEAR(f.imu->accel_FRD_m_s2.y(), 3 * std::sin(phase), 1e-9);
    EXPECT_NEAR(f.imu->accel_FRD_m_s2.z(), -9.81, 1e-9);
  }
}

TEST(SensorFaults, MagScaleMultipliesBeforeTheOffsetAddsBaroOffsetMovesPressureAlt) {
  ActiveFaults a;
  a.mag_scale = 2;
  a.mag_offset_FRD_gauss = {0.05, 0, 0};
  a.baro_offset_Pa = -120;  // about 10 m higher
  auto f = frame_with_everything();
  const auto atmosphere = model::default_world_config().atmosphere;
  SensorFaults(atmosphere).apply(a, 0, f);
  EXPECT_TRUE(f.mag->mag_FRD_gauss.isApprox(Eigen::Vector3d(0.45, 0, 0.8)));
  EXPECT_DOUBLE_EQ(f.baro->pressure_Pa, 94880);
  EXPECT_NEAR(f.baro->pressure_alt_m - model::isa_altitude_m(atmosphere, 95000), 10.5, 0.5);
}

TEST(SensorFaults, GpsDriftWalksThePositionAwayAtItsRateWithAMatchingVelocity) {
  FaultSchedule schedule({*parse_fault("gps-drift:2,-1@10")});
  schedule.update(9.996);
  schedule.update(10.0);
  schedule.update(15.0);
  const auto& a = schedule.active();
  EXPECT_NEAR(a.gps_north_m, 10.0, 1e-9);  // 5 s at 2 m/s
  EXPECT_NEAR(a.gps_east_m, -5.0, 1e-9);
  auto f = frame_with_everything();
  SensorFaults(model::default_world_config().atmosphere).apply(a, 15.0, f);
  EXPECT_NEAR((f.gps->lat_deg - 47.397742) * 111180.0, 10.0, 0.05);
  EXPECT_TRUE(f.gps->v_NED_m_s.isApprox(Eigen::Vector3d(2, -1, 0)));
  EXPECT_NEAR(f.gps->ground_speed_m_s, std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(f.gps->course_over_ground_deg, 360 - 26.565, 1e-3);
}

TEST(SensorFaults, GpsNoiseScalesThePositionAndVelocityErrorsAgainstTruth) {
  const auto vehicle = model::x500_vehicle_config();
  const auto world = model::default_world_config();
  sensors::Gps plain(vehicle.sensors.gps, world.home, 3), scaled(vehicle.sensors.gps, world.home, 3);
  scaled.set_noise_scale(3);
  model::VehicleState state;
  sensors::LocalGeodesy geodesy(world.home);
  const auto truth = geodesy.to_geodetic(state.p_ENU_m);
  for (int i = 0; i < 30; ++i) {
    state.time_s = i / 30.0;
    const auto a = plain.sample(state, state.time_s), b = scaled.sample(state, state.time_s);
    EXPECT_NEAR(b.lat_deg - truth.lat_deg, 3 * (a.lat_deg - truth.lat_deg), 1e-10);
    EXPECT_NEAR(b.alt_m - truth.alt_m, 3 * (a.alt_m - truth.alt_m), 1e-6);
    EXPECT_TRUE(b.v_NED_m_s.isApprox(3 * a.v_NED_m_s));
  }
}

TEST(SensorFaults, ImuNoiseScalesTheErrorsAgainstTruth) {
  const auto vehicle = model::x500_vehicle_config();
  const auto world = model::default_world_config();
  sensors::Imu plain(vehicle.sensors.imu, world, 5), scaled(vehicle.sensors.imu, world, 5), perfect(vehicle.sensors.imu, world, 5);
  scaled.set_noise_scale(4);
  perfect.set_noise_scale(0);
  model::VehicleState state;
  state.specific_force_FLU_m_s2 = {0, 0, 9.81};
  for (int i = 0; i < 50; ++i) {
    state.time_s = i * 0.004;
    const auto a = plain.sample(state, state.time_s), b = scaled.sample(state, state.time_s), c = perfect.sample(state, state.time_s);
    EXPECT_TRUE(c.accel_FRD_m_s2.isApprox(Eigen::Vector3d(0, 0, -9.81)));
    EXPECT_TRUE(c.gyro_FRD_rad_s.isZero());
    EXPECT_TRUE((b.accel_FRD_m_s2 - c.accel_FRD_m_s2).isApprox(4 * (a.accel_FRD_m_s2 - c.accel_FRD_m_s2), 1e-9));
    EXPECT_TRUE(b.gyro_FRD_rad_s.isApprox(4 * a.gyro_FRD_rad_s, 1e-9));
  }
}

TEST(SensorFaults, PropDamageShakesTheImuOncePerRevolutionOfItsRotor) {
  FaultSchedule schedule({*parse_fault("prop-damage:1,0.7,4@0")});
  schedule.update(0);
  const auto& a = schedule.active();
  EXPECT_DOUBLE_EQ(a.motor_effectiveness[1], 0.7);
  SensorFaults faults(model::default_world_config().atmosphere);
  const double omega_rad_s = 2 * M_PI * 30;  // 30 rev/s
  for (int k = 0; k <= 10; ++k) {
    const double t = k * 0.004;
    auto f = frame_with_everything();
    faults.apply(a, t, f, {0, omega_rad_s, 0, 0});
    EXPECT_NEAR(f.imu->accel_FRD_m_s2.x(), 4 * std::cos(omega_rad_s * t), 1e-9) << t;
    EXPECT_NEAR(f.imu->accel_FRD_m_s2.y(), 4 * std::sin(omega_rad_s * t), 1e-9) << t;
  }
}

TEST(FaultSchedule, GustRisesAndFallsAsOneMinusCosineWindAndPayloadAddVioJumpsCountResets) {
  FaultSchedule schedule({*parse_fault("gust:6,0@10+4"), *parse_fault("wind:0,2,-1@0"), *parse_fault("payload:0.3@0"),
                          *parse_fault("vio-jump:1,2,0@1+1"), *parse_fault("actuators-stale@3+1")});
  schedule.update(0);
  EXPECT_TRUE(schedule.active().wind_NED_m_s.isApprox(Eigen::Vector3d(0, 2, -1)));
  EXPECT_DOUBLE_EQ(schedule.active().payload_kg, 0.3);
  schedule.update(1);
  EXPECT_EQ(schedule.active().vio_resets, 1u);
  EXPECT_TRUE(schedule.active().vio_offset_NED_m.isApprox(Eigen::Vector3d(1, 2, 0)));
  schedule.update(2);
  EXPECT_EQ(schedule.active().vio_resets, 2u);  // back: another reset
  EXPECT_TRUE(schedule.active().vio_offset_NED_m.isZero());
  schedule.update(3);
  EXPECT_TRUE(schedule.active().actuators_stale);
  schedule.update(10);
  EXPECT_NEAR(schedule.active().wind_NED_m_s.x(), 0, 1e-9);
  schedule.update(11);
  EXPECT_NEAR(schedule.active().wind_NED_m_s.x(), 3, 1e-9);
  schedule.update(12);
  EXPECT_NEAR(schedule.active().wind_NED_m_s.x(), 6, 1e-9);  // the peak at half the duration
  EXPECT_FALSE(schedule.active().actuators_stale);
  schedule.update(14);
  EXPECT_NEAR(schedule.active().wind_NED_m_s.x(), 0, 1e-9);
  EXPECT_FALSE(parse_fault("gust:6,0@10"));  // a gust needs its duration
}

}  // namespace
}  // namespace hitl::faults
