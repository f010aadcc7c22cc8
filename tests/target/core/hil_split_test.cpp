#include "target/core/hil_split.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/mavlink/hil_sensor_fields.h"

namespace hitl::target {
namespace {

namespace f = mavlink::hil_sensor;

HilSensorInput sensor(uint32_t fields, float value = 1.0F) {
  HilSensorInput m;
  m.time_usec = 123456789;  // ignored by the board
  for (int i = 0; i < 3; ++i) {
    m.accel_FRD_m_s2[i] = value + static_cast<float>(i);
    m.gyro_FRD_rad_s[i] = 0.1F * value + static_cast<float>(i);
    m.mag_FRD_gauss[i] = 0.2F * value + static_cast<float>(i);
  }
  m.abs_pressure_hPa = 1013.25F;
  m.temperature_degC = 21.5F;
  m.fields_updated = fields;
  return m;
}

constexpr uint32_t kImu = f::kAccel | f::kGyro;

/// The IMU grid at the first arrival itself, to keep the arithmetic of most tests plain.
HilSplitConfig no_phase() {
  HilSplitConfig config;
  config.imu_phase_us = 0;
  return config;
}

TEST(HilSplit, NothingBeforeAnyHilSensor) {
  HilSplit split(no_phase());
  EXPECT_TRUE(split.poll(0).empty());
  EXPECT_TRUE(split.poll(1000000).empty());
  EXPECT_EQ(split.next_due_us(), UINT64_MAX);
}

TEST(HilSplit, FirstArrivalPublishesAtOnceStampedOnArrival) {
  HilSplit split;
  split.on_hil_sensor(sensor(kImu | f::kMag | f::kBaro, 2.0F), 500000);
  const HilSplitOutput out = split.poll(500000);
  ASSERT_TRUE(out.mag_baro);
  ASSERT_TRUE(out.battery);
  EXPECT_FALSE(out.imu);  // half a period later
  const HilSplitOutput later = split.poll(502000);
  ASSERT_TRUE(later.imu);
  EXPECT_EQ(later.imu->timestamp, 502000U);  // board time, not HIL_SENSOR.time_usec
  EXPECT_FLOAT_EQ(later.imu->accelerometer_m_s2[0], 2.0F);
  EXPECT_FLOAT_EQ(later.imu->accelerometer_m_s2[2], 4.0F);
  EXPECT_FLOAT_EQ(later.imu->gyroscope_rad_s[1], 1.2F);
  EXPECT_FLOAT_EQ(later.imu->temperature, 21.5F);
  EXPECT_EQ(out.mag_baro->timestamp, 500000U);
  EXPECT_EQ(out.mag_baro->fields_updated, HilSensorMagBaro::FIELD_MAG | HilSensorMagBaro::FIELD_BARO);
  EXPECT_FLOAT_EQ(out.mag_baro->magnetometer_ga[0], 0.4F);
  EXPECT_FLOAT_EQ(out.mag_baro->pressure_pa, 101325.0F);  // hPa -> Pa
  EXPECT_FLOAT_EQ(out.mag_baro->temperature, 21.5F);
}

TEST(HilSplit, ImuGridSitsMidPeriodBetweenHostArrivals) {
  HilSplit split;  // imu_phase_us 2000
  // A 250 Hz host whose arrivals wander +-750 us around the first one's phase.
  auto arrival_us = [](uint64_t k) { return 10000 + k * 4000 + (k == 0 ? 750 : (k * 7919) % 1500); };
  uint64_t k = 0;
  int published = 0;
  for (uint64_t t = 10000; t < 10000 + 250 * 4000; t += 50) {
    if (t >= arrival_us(k)) split.on_hil_sensor(sensor(kImu, static_cast<float>(k++)), t);
    const auto out = split.poll(t);
    if (out.imu) {
      EXPECT_FLOAT_EQ(out.imu->accelerometer_m_s2[0], static_cast<float>(published));  // each sample once
      ++published;
    }
  }
  EXPECT_EQ(published, 250);
  EXPECT_EQ(split.counters().imu_repeated, 0U);
  EXPECT_EQ(split.counters().imu_overwritten, 0U);
}

TEST(HilSplit, PressureConversion) {
  EXPECT_FLOAT_EQ(pressure_Pa_from_hPa(1013.25F), 101325.0F);
  EXPECT_FLOAT_EQ(pressure_Pa_from_hPa(0.0F), 0.0F);
}

TEST(HilSplit, ImuEvery4000usWithTheLatestValues) {
  HilSplit split(no_phase());
  split.on_hil_sensor(sensor(kImu, 1.0F), 0);
  ASSERT_TRUE(split.poll(0).imu);
  EXPECT_EQ(split.next_due_us(), 4000U);
  split.on_hil_sensor(sensor(kImu, 5.0F), 1000);
  split.on_hil_sensor(sensor(kImu, 7.0F), 3000);  // replaces 5.0 before publication
  EXPECT_FALSE(split.poll(3999).imu);
  const auto out = split.poll(4000);
  ASSERT_TRUE(out.imu);
  EXPECT_FLOAT_EQ(out.imu->accelerometer_m_s2[0], 7.0F);
  EXPECT_EQ(split.counters().imu_overwritten, 1U);
  EXPECT_EQ(split.counters().imu_published, 2U);
  EXPECT_EQ(split.counters().imu_repeated, 0U);
}

TEST(HilSplit, ImuRepeatsLatestWhenNothingNewThenStopsAfterHoldLimit) {
  HilSplitConfig config = no_phase();
  config.hold_limit_us = 20000;
  HilSplit split(config);
  split.on_hil_sensor(sensor(kImu, 3.0F), 0);
  int published = 0;
  for (uint64_t t = 0; t <= 40000; t += 1000) {
    const auto out = split.poll(t);
    if (out.imu) {
      ++published;
      EXPECT_FLOAT_EQ(out.imu->accelerometer_m_s2[0], 3.0F);
      EXPECT_LE(t, 20000U);
    }
  }
  EXPECT_EQ(published, 6);  // 0, 4000, ..., 20000
  EXPECT_EQ(split.counters().imu_repeated, 5U);

  // The host comes back: publication resumes at once, on a new grid.
  split.on_hil_sensor(sensor(kImu, 4.0F), 41500);
  const auto out = split.poll(41500);
  ASSERT_TRUE(out.imu);
  EXPECT_FLOAT_EQ(out.imu->accelerometer_m_s2[0], 4.0F);
  EXPECT_EQ(split.next_due_us(), 45500U);
}

TEST(HilSplit, ImuWaitsForBothAccelAndGyro) {
  HilSplit split(no_phase());
  split.on_hil_sensor(sensor(f::kAccel), 0);
  EXPECT_FALSE(split.poll(0).imu);
  EXPECT_FALSE(split.poll(4000).imu);
  split.on_hil_sensor(sensor(f::kGyro, 2.0F), 5000);
  const auto out = split.poll(5000);
  ASSERT_TRUE(out.imu);
  EXPECT_FLOAT_EQ(out.imu->accelerometer_m_s2[0], 1.0F);  // accel from the first message
  EXPECT_FLOAT_EQ(out.imu->gyroscope_rad_s[0], 0.2F);     // gyro from the second
}

TEST(HilSplit, MagBaroEvery10000usWithBitsOnlyForWhatIsNew) {
  HilSplit split(no_phase());
  split.on_hil_sensor(sensor(kImu | f::kMag | f::kBaro), 0);
  EXPECT_EQ(split.poll(0).mag_baro->fields_updated, 3);

  split.on_hil_sensor(sensor(kImu | f::kMag, 2.0F), 4000);
  EXPECT_FALSE(split.poll(9999).mag_baro);
  auto out = split.poll(10000);
  ASSERT_TRUE(out.mag_baro);
  EXPECT_EQ(out.mag_baro->fields_updated, HilSensorMagBaro::FIELD_MAG);
  EXPECT_FLOAT_EQ(out.mag_baro->magnetometer_ga[0], 0.4F);
  EXPECT_FLOAT_EQ(out.mag_baro->pressure_pa, 101325.0F);  // latest baro, not flagged as new

  split.on_hil_sensor(sensor(kImu | f::kBaro), 12000);
  out = split.poll(20000);
  ASSERT_TRUE(out.mag_baro);
  EXPECT_EQ(out.mag_baro->fields_updated, HilSensorMagBaro::FIELD_BARO);

  // Nothing new: still published (100 Hz batched), fields_updated 0.
  split.on_hil_sensor(sensor(kImu), 24000);
  out = split.poll(30000);
  ASSERT_TRUE(out.mag_baro);
  EXPECT_EQ(out.mag_baro->fields_updated, 0);

  const HilSplitCounters c = split.counters();
  EXPECT_EQ(c.mag_baro_published, 4U);
  EXPECT_EQ(c.mag_published, 2U);
  EXPECT_EQ(c.baro_published, 2U);
  EXPECT_EQ(c.mag_received, 2U);
  EXPECT_EQ(c.baro_received, 2U);
}

TEST(HilSplit, TwoMagsInOneBatchSetTheBitOnceAndCountTheOverwrite) {
  HilSplit split(no_phase());
  split.on_hil_sensor(sensor(kImu), 0);
  split.poll(0);
  split.on_hil_sensor(sensor(f::kMag, 1.0F), 2000);
  split.on_hil_sensor(sensor(f::kMag, 3.0F), 6000);
  const auto out = split.poll(10000);
  ASSERT_TRUE(out.mag_baro);
  EXPECT_EQ(out.mag_baro->fields_updated, HilSensorMagBaro::FIELD_MAG);
  EXPECT_FLOAT_EQ(out.mag_baro->magnetometer_ga[0], 0.6F);
  EXPECT_EQ(split.counters().mag_overwritten, 1U);
  EXPECT_EQ(split.counters().mag_published, 1U);
}

TEST(HilSplit, PartialGroupsAreIgnoredAndCounted) {
  HilSplit split(no_phase());
  // Baro without temperature (0x0A00) and mag without z: neither counts.
  split.on_hil_sensor(sensor(kImu | f::kXMag | f::kYMag | f::kAbsPressure | f::kPressureAlt), 0);
  const auto out = split.poll(0);
  ASSERT_TRUE(out.mag_baro);
  EXPECT_EQ(out.mag_baro->fields_updated, 0);
  EXPECT_TRUE(std::isnan(out.mag_baro->magnetometer_ga[0]));  // never received
  EXPECT_TRUE(std::isnan(out.mag_baro->pressure_pa));
  EXPECT_TRUE(std::isnan(out.mag_baro->temperature));
  EXPECT_TRUE(std::isnan(out.imu->temperature));
  EXPECT_EQ(split.counters().partial_groups, 2U);
  EXPECT_EQ(split.counters().mag_received, 0U);
  EXPECT_EQ(split.counters().baro_received, 0U);
}

TEST(HilSplit, BatteryAt10HzWhileHilSensorArrives) {
  HilSplitConfig config = no_phase();
  config.hold_limit_us = 100000;
  HilSplit split(config);
  int batteries = 0;
  for (uint64_t t = 0; t < 1000000; t += 4000) {
    split.on_hil_sensor(sensor(kImu), t);
    const auto out = split.poll(t);
    if (out.battery) {
      ++batteries;
      EXPECT_EQ(out.battery->timestamp_us, t);
      EXPECT_FLOAT_EQ(out.battery->voltage_V, 16.8F);
      EXPECT_FLOAT_EQ(out.battery->current_A, 5.0F);
      EXPECT_FLOAT_EQ(out.battery->remaining_ratio, 1.0F);
    }
  }
  EXPECT_EQ(batteries, 10);
  // The host stops at 996000: nothing of anything once the data are over 100 ms old.
  for (uint64_t t = 1000000; t < 1100000; t += 1000) split.poll(t);
  EXPECT_TRUE(split.poll(1100000).empty());
  EXPECT_TRUE(split.poll(2000000).empty());
}

TEST(HilSplit, NextDueIsTheEarliestStream) {
  HilSplit split(no_phase());
  split.on_hil_sensor(sensor(kImu), 1000);
  split.poll(1000);
  EXPECT_EQ(split.next_due_us(), 5000U);
}

TEST(HilSplit, LatePollResyncsWithoutBurst) {
  HilSplit split(no_phase());
  split.on_hil_sensor(sensor(kImu), 0);
  split.poll(0);
  split.on_hil_sensor(sensor(kImu), 30000);
  const auto out = split.poll(30000);  // 7 IMU periods late: one message, not seven
  EXPECT_TRUE(out.imu);
  EXPECT_FALSE(split.poll(30000).imu);
  EXPECT_EQ(split.counters().imu_published, 2U);
  EXPECT_GE(split.counters().resyncs, 1U);
}

TEST(HilSplit, PollTimeoutIsTheWaitToTheNextDueRoundedUpToWholeMs) {
  HilSplit split;  // IMU grid half a period after the first arrival
  EXPECT_EQ(split.poll_timeout_ms(0, 10), 10);  // nothing live: the loop's own timeout
  split.on_hil_sensor(sensor(kImu | f::kMag), 1000);
  EXPECT_EQ(split.poll_timeout_ms(1000, 10), 0);  // mag/baro and battery are due at once
  split.poll(1000);
  EXPECT_EQ(split.poll_timeout_ms(1000, 10), 2);  // the IMU at 3000
  EXPECT_EQ(split.poll_timeout_ms(1500, 10), 2);  // 1.5 ms rounds up: at most 1 ms late, never early
  EXPECT_EQ(split.poll_timeout_ms(2999, 10), 1);
  EXPECT_EQ(split.poll_timeout_ms(3000, 10), 0);
  EXPECT_EQ(split.poll_timeout_ms(1000, 1), 1);   // capped by the caller's timeout
  EXPECT_EQ(split.poll_timeout_ms(1000, -5), 0);  // a negative cap is no wait, not poll's "forever"
  // The host goes quiet: each stream stops at its first due time past the 100 ms hold limit (the
  // battery's at 201000), then the loop's own timeout again.
  for (uint64_t t = 2000; t <= 201000; t += 1000) split.poll(t);
  EXPECT_EQ(split.poll_timeout_ms(201000, 10), 10);
}

// PX4's MavlinkReceiver with the patch: poll(2) for at most poll_timeout_ms, publish what is due,
// then hand over what arrived. With a 250 Hz host jittering by up to +-0.8 ms every HIL_SENSOR is
// published exactly once, at most 1 ms after its due time.
TEST(HilSplit, ReceiveLoopPublishesEveryArrivalOnceOnTime) {
  HilSplit split;
  constexpr int kArrivals = 1000;
  std::vector<uint64_t> arrivals_us;
  uint32_t lcg = 12345;  // a fixed jitter sequence, the same on every standard library
  for (int k = 0; k < kArrivals; ++k) {
    lcg = lcg * 1664525U + 1013904223U;
    const int64_t jitter_us = (k == 0) ? 0 : static_cast<int64_t>(lcg >> 16) % 1601 - 800;
    arrivals_us.push_back(static_cast<uint64_t>(1000000 + 4000 * k + jitter_us));
  }
  uint64_t now_us = 0;
  std::size_t next = 0;
  uint64_t published = 0;
  uint64_t max_late_us = 0;
  uint64_t due_us = UINT64_MAX;
  int iterations = 0;
  while ((next < arrivals_us.size() || split.next_due_us() != UINT64_MAX) && ++iterations < 100000) {
    const int timeout_ms = split.poll_timeout_ms(now_us, 10);
    uint64_t wake_us = now_us + static_cast<uint64_t>(timeout_ms) * 1000U;
    if (next < arrivals_us.size() && arrivals_us[next] < wake_us) wake_us = arrivals_us[next];
    now_us = std::max(now_us, wake_us);
    due_us = split.next_due_us();
    const HilSplitOutput out = split.poll(now_us);
    if (out.imu) {
      ++published;
      max_late_us = std::max(max_late_us, now_us - due_us);
    }
    while (next < arrivals_us.size() && arrivals_us[next] <= now_us) {
      split.on_hil_sensor(sensor(kImu, static_cast<float>(next)), now_us);
      ++next;
    }
  }
  ASSERT_LT(iterations, 100000) << "the loop did not end; now " << now_us << " us";
  const HilSplitCounters c = split.counters();
  EXPECT_EQ(c.imu_overwritten, 0U);
  EXPECT_EQ(c.resyncs, 0U);
  // Every arrival once, then the last values repeated until the 100 ms hold limit ends the stream.
  EXPECT_EQ(published - c.imu_repeated, static_cast<uint64_t>(kArrivals));
  EXPECT_LE(c.imu_repeated, 26U);
  EXPECT_LE(max_late_us, 1000U);
}

}  // namespace
}  // namespace hitl::target
