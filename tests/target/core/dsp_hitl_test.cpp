#include "target/core/dsp_hitl.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/contract/device_ids.h"

namespace hitl::target {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

HilSensorImu imu(float ax, float gz, float temperature = 30.0F) {
  HilSensorImu m;
  m.timestamp = 42;  // apps-processor time: never reused on the DSP
  m.accelerometer_m_s2[0] = ax;
  m.accelerometer_m_s2[1] = 0.1F;
  m.accelerometer_m_s2[2] = -9.81F;
  m.gyroscope_rad_s[0] = 0.01F;
  m.gyroscope_rad_s[1] = 0.02F;
  m.gyroscope_rad_s[2] = gz;
  m.temperature = temperature;
  return m;
}

HilSensorMagBaro mag_baro(uint8_t fields, float temperature = 20.0F) {
  HilSensorMagBaro m;
  m.timestamp = 42;
  m.magnetometer_ga[0] = 0.21F;
  m.magnetometer_ga[1] = 0.01F;
  m.magnetometer_ga[2] = 0.43F;
  m.pressure_pa = 101325.0F;
  m.temperature = temperature;
  m.fields_updated = fields;
  return m;
}

DspHitl started() {
  DspHitl d;
  d.start();
  return d;
}

TEST(DspHitl, ImuBecomesAccelAndGyroWithFreshTimestamps) {
  DspHitl d = started();
  const auto out = d.on_imu(imu(-0.25F, 0.003F), 9000);
  ASSERT_TRUE(out);
  EXPECT_EQ(out->accel.timestamp_us, 9000U);
  EXPECT_EQ(out->accel.timestamp_sample_us, 9000U);
  EXPECT_EQ(out->gyro.timestamp_us, 9000U);
  EXPECT_EQ(out->gyro.timestamp_sample_us, 9000U);
  EXPECT_EQ(out->accel.device_id, 1310988U);
  EXPECT_EQ(out->gyro.device_id, 1310988U);
  EXPECT_FLOAT_EQ(out->accel.accel_FRD_m_s2[0], -0.25F);
  EXPECT_FLOAT_EQ(out->accel.accel_FRD_m_s2[2], -9.81F);
  EXPECT_FLOAT_EQ(out->gyro.gyro_FRD_rad_s[2], 0.003F);
  EXPECT_FLOAT_EQ(out->accel.temperature_degC, 30.0F);
  EXPECT_EQ(d.counters().hil_imu_received, 1U);
  EXPECT_EQ(d.counters().imu_published, 1U);
}

TEST(DspHitl, ImuKeepsTheLastFiniteTemperature) {
  DspHitl d = started();
  d.on_imu(imu(0, 0, 30.0F), 1000);
  const auto out = d.on_imu(imu(0, 0, kNaN), 5000);
  ASSERT_TRUE(out);
  EXPECT_FLOAT_EQ(out->gyro.temperature_degC, 30.0F);
}

TEST(DspHitl, MagAndBaroOnlyByTheirBits) {
  DspHitl d = started();
  auto out = d.on_mag_baro(mag_baro(0), 1000);
  EXPECT_FALSE(out.mag);
  EXPECT_FALSE(out.baro);

  out = d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_MAG), 11000);
  ASSERT_TRUE(out.mag);
  EXPECT_FALSE(out.baro);
  EXPECT_EQ(out.mag->device_id, 197388U);
  EXPECT_EQ(out.mag->timestamp_us, 11000U);
  EXPECT_EQ(out.mag->timestamp_sample_us, 11000U);
  EXPECT_FLOAT_EQ(out.mag->mag_FRD_gauss[2], 0.43F);

  out = d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_BARO), 21000);
  EXPECT_FALSE(out.mag);
  ASSERT_TRUE(out.baro);
  EXPECT_EQ(out.baro->device_id, 6620172U);
  EXPECT_EQ(out.baro->timestamp_us, 21000U);
  EXPECT_FLOAT_EQ(out.baro->pressure_Pa, 101325.0F);
  EXPECT_FLOAT_EQ(out.baro->temperature_degC, 20.0F);

  out = d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_MAG | HilSensorMagBaro::FIELD_BARO), 31000);
  EXPECT_TRUE(out.mag);
  EXPECT_TRUE(out.baro);

  const DspHitlCounters& c = d.counters();
  EXPECT_EQ(c.hil_mag_baro_received, 4U);
  EXPECT_EQ(c.mag_published, 2U);
  EXPECT_EQ(c.baro_published, 2U);
}

TEST(DspHitl, BaroWithoutTemperatureGetsIsaDefault) {
  DspHitl d = started();
  const auto out = d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_BARO, kNaN), 1000);
  ASSERT_TRUE(out.baro);
  EXPECT_FLOAT_EQ(out.baro->temperature_degC, DspHitl::kBaroTemperatureDefault_degC);
}

TEST(DspHitl, NonFiniteValuesAreReceivedButNotPublished) {
  DspHitl d = started();
  EXPECT_FALSE(d.on_imu(imu(kNaN, 0), 1000));
  HilSensorMagBaro m = mag_baro(HilSensorMagBaro::FIELD_MAG | HilSensorMagBaro::FIELD_BARO);
  m.magnetometer_ga[1] = std::numeric_limits<float>::infinity();
  m.pressure_pa = kNaN;
  const auto out = d.on_mag_baro(m, 2000);
  EXPECT_FALSE(out.mag);
  EXPECT_FALSE(out.baro);
  const DspHitlCounters& c = d.counters();
  EXPECT_EQ(c.hil_imu_received, 1U);
  EXPECT_EQ(c.imu_published, 0U);
  EXPECT_EQ(c.hil_mag_baro_received, 1U);
  EXPECT_EQ(c.mag_published, 0U);
  EXPECT_EQ(c.baro_published, 0U);
  EXPECT_EQ(c.not_finite, 3U);
}

TEST(DspHitl, TimestampsStrictlyIncreasePerSensor) {
  DspHitl d = started();
  EXPECT_TRUE(d.on_imu(imu(1, 0), 0));  // the very first may be at time 0
  EXPECT_FALSE(d.on_imu(imu(2, 0), 0));  // same DSP time: received, not published
  EXPECT_TRUE(d.on_imu(imu(3, 0), 1));
  EXPECT_EQ(d.counters().hil_imu_received, 3U);
  EXPECT_EQ(d.counters().imu_published, 2U);
  EXPECT_EQ(d.counters().time_not_advanced, 1U);
  EXPECT_FLOAT_EQ(d.current().accel_FRD_m_s2[0], 3.0F);

  // Mag and baro are tracked separately: a baro at the time of the last mag is fine.
  EXPECT_TRUE(d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_MAG), 500).mag);
  EXPECT_TRUE(d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_BARO), 500).baro);
  EXPECT_FALSE(d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_MAG), 500).mag);
}

TEST(DspHitl, IgnoresInputWhileStoppedAndKeepsCountersOverStop) {
  DspHitl d;
  EXPECT_FALSE(d.running());
  EXPECT_FALSE(d.on_imu(imu(1, 0), 1000));
  EXPECT_EQ(d.counters().hil_imu_received, 0U);
  d.start();
  EXPECT_TRUE(d.on_imu(imu(1, 0), 2000));
  d.stop();
  EXPECT_FALSE(d.running());
  EXPECT_FALSE(d.on_mag_baro(mag_baro(HilSensorMagBaro::FIELD_MAG), 3000).mag);
  EXPECT_EQ(d.counters().hil_imu_received, 1U);
  EXPECT_EQ(d.counters().hil_mag_baro_received, 0U);
  d.clear_counters();
  EXPECT_EQ(d.counters().hil_imu_received, 0U);
  EXPECT_EQ(d.counters().imu_published, 0U);
}

}  // namespace
}  // namespace hitl::target
