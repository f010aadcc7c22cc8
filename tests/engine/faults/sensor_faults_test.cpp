// The sensor faults on a sampled frame: what a bias, an offset, a lost or jumped GPS does to it.
#include <gtest/gtest.h>

#include "engine/faults/sensor_faults.h"
#include "engine/model/atmosphere.h"
#include "engine/model/x500_defaults.h"

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
  apply_sensor_faults(a, atmosphere, f);
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
  apply_sensor_faults(loss, atmosphere, f);
  EXPECT_FALSE(f.gps);
  EXPECT_TRUE(f.imu);

  ActiveFaults jump;
  jump.gps_north_m = 100;
  jump.gps_east_m = -50;
  jump.gps_report = GpsReport{2, 4, 5.0, 8.0};
  auto g = frame_with_everything();
  apply_sensor_faults(jump, atmosphere, g);
  // 1 deg of latitude at 47.4 N is 111,180 m; 1 deg of longitude there 75,330 m.
  EXPECT_NEAR((g.gps->lat_deg - 47.397742) * 111180.0, 100.0, 0.5);
  EXPECT_NEAR((g.gps->lon_deg - 8.545594) * 75330.0, -50.0, 0.5);
  EXPECT_EQ(g.gps->fix_type, 2);
  EXPECT_EQ(g.gps->satellites, 4);
  EXPECT_DOUBLE_EQ(g.gps->eph_m, 5.0);
  EXPECT_DOUBLE_EQ(g.gps->epv_m, 8.0);
}

}  // namespace
}  // namespace hitl::faults
