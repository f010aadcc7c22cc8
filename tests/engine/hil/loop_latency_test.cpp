// LoopLatency (engine/hil/loop_latency.h): which HIL_ACTUATOR_CONTROLS answers which HIL_SENSOR,
// in lockstep by the time_usec echo and outside it the next one, on made-up clocks.
#include "engine/hil/loop_latency.h"

#include <gtest/gtest.h>

namespace hitl::hil {
namespace {

TEST(LoopLatency, LockstepMatchesTheEchoExactly) {
  LoopLatency l(true);
  for (uint64_t k = 1; k <= 100; ++k) {
    const double sent = static_cast<double>(k) * 0.004;
    l.on_hil_sensor_sent(k * 4000, sent);
    l.on_actuator(k * 4000, sent + 0.0005);  // answered 500 us later
  }
  const auto s = l.summary();
  EXPECT_TRUE(s.lockstep);
  EXPECT_EQ(s.sensors, 100u);
  EXPECT_EQ(s.unanswered, 0u);
  EXPECT_EQ(s.latency.count, 100u);
  EXPECT_NEAR(s.latency.p50_us, 500, 1e-6);
  EXPECT_NEAR(s.latency.max_us, 500, 1e-6);
}

TEST(LoopLatency, LockstepAnswerOfAnOlderSensorIsNotCountedTwice) {
  LoopLatency l(true);
  l.on_hil_sensor_sent(4000, 0.0);
  l.on_actuator(4000, 0.001);
  l.on_hil_sensor_sent(8000, 0.004);
  l.on_actuator(4000, 0.0045);  // late: a second answer to the first
  l.on_actuator(8000, 0.006);
  const auto s = l.summary();
  EXPECT_EQ(s.latency.count, 2u);
  EXPECT_NEAR(s.latency.max_us, 2000, 1e-6);
  EXPECT_EQ(s.unanswered, 0u);
}

TEST(LoopLatency, LockstepSkippedSensorsAreUnanswered) {
  LoopLatency l(true);
  l.on_hil_sensor_sent(4000, 0.0);
  l.on_hil_sensor_sent(8000, 0.004);
  l.on_hil_sensor_sent(12000, 0.008);
  l.on_actuator(12000, 0.009);  // the board answered the last only
  const auto s = l.summary();
  EXPECT_EQ(s.latency.count, 1u);
  EXPECT_NEAR(s.latency.max_us, 1000, 1e-6);
  EXPECT_EQ(s.unanswered, 2u);
}

TEST(LoopLatency, OwnClockOrRealTimeAnswersEveryWaitingSensor) {
  for (bool lockstep : {false, true}) {  // lockstep with a board on its own clock (a PX4 board in HIL mode)
    LoopLatency l(lockstep);
    l.on_hil_sensor_sent(4000, 0.000);
    l.on_hil_sensor_sent(8000, 0.004);
    l.on_actuator(987654321, 0.005);  // the next message answers both
    l.on_actuator(987659321, 0.006);  // nothing waits: not a sample
    const auto s = l.summary();
    EXPECT_EQ(s.latency.count, 2u) << lockstep;
    EXPECT_NEAR(s.latency.min_us, 1000, 1e-6);
    EXPECT_NEAR(s.latency.max_us, 5000, 1e-6);
    EXPECT_EQ(s.unanswered, 0u);
  }
}

TEST(LoopLatency, BoundedWhenNothingAnswers) {
  LoopLatency l(false);
  for (uint64_t k = 0; k < 10 * LoopLatency::kMaxPending; ++k) l.on_hil_sensor_sent(k * 4000, static_cast<double>(k) * 0.004);
  const auto s = l.summary();
  EXPECT_EQ(s.sensors, 10 * LoopLatency::kMaxPending);
  EXPECT_EQ(s.unanswered, 10 * LoopLatency::kMaxPending);
  EXPECT_EQ(s.latency.count, 0u);
}

}  // namespace
}  // namespace hitl::hil
