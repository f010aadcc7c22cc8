// The whole board path in simulated time: a host sending HIL_SENSOR at the spec's rates (IMU 250,
// mag 50, baro 10 Hz) with jitter, the apps-processor split, MUORB as a depth-one topic, and
// dsp_hitl polling every 4 ms. Checks the rates of the spec's "Data Flow Rates" table.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>

#include "base/mavlink/hil_sensor_fields.h"
#include "target/core/dsp_hitl.h"
#include "target/core/hil_split.h"

namespace hitl::target {
namespace {

namespace f = mavlink::hil_sensor;

TEST(Pipeline, TenSecondsAtTheSpecsRates) {
  HilSplit split;
  DspHitl dsp;
  dsp.start();

  std::optional<HilSensorImu> imu_topic;  // latest unseen hil_sensor_imu (MUORB, queue depth 1)
  std::optional<HilSensorMagBaro> mag_baro_topic;
  uint64_t batteries = 0;
  uint64_t host_k = 0;      // host IMU tick
  uint64_t next_dsp_poll_us = 1700;
  const uint64_t end_us = 10000000;

  for (uint64_t t = 0; t < end_us; t += 100) {  // 100 us resolution
    // Host: one HIL_SENSOR per 4 ms with up to 300 us jitter; mag every 5th, baro every 25th.
    const uint64_t jitter_us = (host_k * 7919) % 300;  // arrives at the first step at or after
    if (t >= host_k * 4000 + jitter_us) {
      HilSensorInput msg;
      msg.fields_updated = f::kAccel | f::kGyro;
      if (host_k % 5 == 0) msg.fields_updated |= f::kMag;
      if (host_k % 25 == 0) msg.fields_updated |= f::kBaro;
      msg.accel_FRD_m_s2[2] = -9.81F + 0.001F * static_cast<float>(host_k % 10);
      msg.abs_pressure_hPa = 1013.25F;
      split.on_hil_sensor(msg, t);
      ++host_k;
    }
    // Apps processor.
    const HilSplitOutput out = split.poll(t);
    if (out.imu) imu_topic = out.imu;
    if (out.mag_baro) mag_baro_topic = out.mag_baro;
    if (out.battery) ++batteries;
    // DSP: polls both topics every 4 ms.
    if (t == next_dsp_poll_us) {
      if (imu_topic) dsp.on_imu(*imu_topic, t);
      if (mag_baro_topic) dsp.on_mag_baro(*mag_baro_topic, t);
      imu_topic.reset();
      mag_baro_topic.reset();
      next_dsp_poll_us += 4000;
    }
  }

  const HilSplitCounters s = split.counters();
  EXPECT_EQ(s.hil_sensor_received, 2500U);
  EXPECT_EQ(s.imu_published, 2500U);
  EXPECT_EQ(s.imu_repeated, 0U);     // jitter well inside the half period either side
  EXPECT_EQ(s.imu_overwritten, 0U);
  EXPECT_EQ(s.mag_baro_published, 1000U);  // 100 Hz batched
  EXPECT_EQ(s.mag_published, 500U);        // 50 Hz
  EXPECT_EQ(s.baro_published, 100U);       // 10 Hz
  EXPECT_EQ(batteries, 100U);              // 10 Hz
  EXPECT_EQ(s.resyncs, 0U);

  const DspHitlCounters& d = dsp.counters();
  EXPECT_NEAR(static_cast<double>(d.hil_imu_received), 2500, 2);
  EXPECT_EQ(d.imu_published, d.hil_imu_received);
  EXPECT_EQ(d.hil_mag_baro_received, 1000U);
  EXPECT_EQ(d.mag_published, 500U);
  EXPECT_EQ(d.baro_published, 100U);
}

}  // namespace
}  // namespace hitl::target
