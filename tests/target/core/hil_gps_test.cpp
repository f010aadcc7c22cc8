#include "target/core/hil_gps.h"

#include <gtest/gtest.h>

#include <cmath>

#include "base/contract/device_ids.h"

namespace hitl::target {
namespace {

constexpr double kPi = 3.14159265358979323846;

HilGpsInput zurich() {
  HilGpsInput g;
  g.time_usec = 1700000000000000ULL;
  g.fix_type = 3;
  g.lat_degE7 = 473977418;
  g.lon_degE7 = 85455939;
  g.alt_mm = 488123;
  g.eph_cm = 30;
  g.epv_cm = 40;
  g.vel_cm_s = 500;
  g.vn_cm_s = 300;
  g.ve_cm_s = -400;
  g.vd_cm_s = -25;
  g.cog_cdeg = 9000;
  g.satellites_visible = 10;
  return g;
}

TEST(HilGps, ConvertsWireUnitsToSi) {
  const SensorGps gps = to_sensor_gps(zurich(), 777);
  EXPECT_EQ(gps.timestamp_us, 777U);
  EXPECT_EQ(gps.time_utc_us, 1700000000000000ULL);
  EXPECT_EQ(gps.device_id, kDeviceIdGps);
  EXPECT_EQ(gps.device_id, 11468804U);
  EXPECT_NEAR(gps.latitude_deg, 47.3977418, 1e-9);
  EXPECT_NEAR(gps.longitude_deg, 8.5455939, 1e-9);
  EXPECT_NEAR(gps.altitude_msl_m, 488.123, 1e-9);
  EXPECT_DOUBLE_EQ(gps.altitude_ellipsoid_m, gps.altitude_msl_m);
  EXPECT_FLOAT_EQ(gps.eph_m, 0.30F);
  EXPECT_FLOAT_EQ(gps.epv_m, 0.40F);
  EXPECT_FLOAT_EQ(gps.vel_m_s, 5.0F);
  EXPECT_FLOAT_EQ(gps.vel_n_m_s, 3.0F);
  EXPECT_FLOAT_EQ(gps.vel_e_m_s, -4.0F);
  EXPECT_FLOAT_EQ(gps.vel_d_m_s, -0.25F);
  EXPECT_NEAR(gps.cog_rad, kPi / 2, 1e-6);
  EXPECT_TRUE(gps.vel_ned_valid);
  EXPECT_EQ(gps.fix_type, 3);
  EXPECT_EQ(gps.satellites_used, 10);
  EXPECT_FLOAT_EQ(gps.s_variance_m_s, 0.25F);
  EXPECT_FLOAT_EQ(gps.c_variance_rad, 0.5F);
  EXPECT_TRUE(std::isnan(gps.heading_rad));
}

TEST(HilGps, CourseOverGround) {
  EXPECT_TRUE(std::isnan(cog_rad_from_cdeg(65535)));
  EXPECT_FLOAT_EQ(cog_rad_from_cdeg(0), 0.0F);
  EXPECT_NEAR(cog_rad_from_cdeg(18000), kPi, 1e-6);
  EXPECT_NEAR(cog_rad_from_cdeg(35999), 2 * kPi * 35999 / 36000, 1e-6);
  EXPECT_NEAR(cog_rad_from_cdeg(36000), 0.0, 1e-6);  // wraps like PX4's wrap_2pi
  EXPECT_LT(cog_rad_from_cdeg(35999), static_cast<float>(2 * kPi));
}

TEST(HilGps, NegativeCoordinatesAndUnknownAccuracy) {
  HilGpsInput g = zurich();
  g.lat_degE7 = -337000000;
  g.lon_degE7 = -1799999999;
  g.alt_mm = -12000;
  g.eph_cm = 65535;  // unknown: passes through as 655.35 m, as PX4 does
  const SensorGps gps = to_sensor_gps(g, 0);
  EXPECT_NEAR(gps.latitude_deg, -33.7, 1e-9);
  EXPECT_NEAR(gps.longitude_deg, -179.9999999, 1e-9);
  EXPECT_NEAR(gps.altitude_msl_m, -12.0, 1e-9);
  EXPECT_FLOAT_EQ(gps.eph_m, 655.35F);
}

}  // namespace
}  // namespace hitl::target
