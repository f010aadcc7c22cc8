// compare_actuators (engine/replay/actuator_compare.h) on made-up answers.
#include "engine/replay/actuator_compare.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hitl::replay {
namespace {

std::vector<RecordedStep> steps(int n) {
  std::vector<RecordedStep> s(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) s[static_cast<std::size_t>(k)].sensor_time_usec = static_cast<uint64_t>(k + 1) * 4000;
  return s;
}

ActuatorSample answer(uint64_t time_usec, int64_t step, float u0, float u2 = 0) {
  ActuatorSample a;
  a.time_usec = time_usec;
  a.step = step;
  a.controls = {u0, 0, u2, 0};
  return a;
}

TEST(ActuatorCompare, TheSameAnswersAreIdentical) {
  const auto s = steps(10);
  std::vector<ActuatorSample> a;
  for (int k = 0; k < 10; ++k) a.push_back(answer(s[static_cast<std::size_t>(k)].sensor_time_usec, k, 0.1f * static_cast<float>(k)));
  const auto c = compare_actuators(s, a, a, 0);
  EXPECT_TRUE(c.by_echo);
  EXPECT_EQ(c.steps_compared, 10u);
  EXPECT_TRUE(c.identical());
  EXPECT_EQ(c.motors[0].max_abs, 0);
}

TEST(ActuatorCompare, MaxRmsAndTheFirstDivergence) {
  const auto s = steps(4);
  std::vector<ActuatorSample> rec, now;
  for (int k = 0; k < 4; ++k) {
    rec.push_back(answer(s[static_cast<std::size_t>(k)].sensor_time_usec, k, 0.5f, 0.2f));
    now.push_back(answer(s[static_cast<std::size_t>(k)].sensor_time_usec, k, 0.5f, k >= 2 ? 0.4f : 0.2f));
  }
  const auto c = compare_actuators(s, rec, now, 0);
  ASSERT_TRUE(c.first_divergence);
  EXPECT_NEAR(c.first_divergence->t_s, 0.012, 1e-12);  // step 2's time
  EXPECT_EQ(c.first_divergence->motor, 2);
  EXPECT_NEAR(c.first_divergence->recorded, 0.2, 1e-6);
  EXPECT_NEAR(c.first_divergence->replayed, 0.4, 1e-6);
  EXPECT_NEAR(c.motors[2].max_abs, 0.2, 1e-6);
  EXPECT_NEAR(c.motors[2].rms, std::sqrt(2 * 0.04 / 4), 1e-6);
  EXPECT_EQ(c.motors[0].max_abs, 0);
  EXPECT_FALSE(c.identical());
  EXPECT_TRUE(compare_actuators(s, rec, now, 0.25).identical());  // within a tolerance
}

TEST(ActuatorCompare, ByStepWhenTheBoardStampsItsOwnClockAndMissingAnswersCount) {
  const auto s = steps(3);
  const std::vector<ActuatorSample> rec = {answer(111, 0, 0.1f), answer(222, 0, 0.2f), answer(333, 1, 0.3f), answer(444, 2, 0.4f)};
  const std::vector<ActuatorSample> now = {answer(999, 0, 0.2f), answer(998, 2, 0.4f)};
  const auto c = compare_actuators(s, rec, now, 0);
  EXPECT_FALSE(c.by_echo);
  EXPECT_EQ(c.steps_compared, 3u);  // the controls in effect at each step: 0.2, 0.3 | 0.2 (held), 0.4
  EXPECT_EQ(c.missing, 0u);
  ASSERT_TRUE(c.first_divergence);
  EXPECT_NEAR(c.first_divergence->t_s, 0.008, 1e-12);  // step 1: 0.3 recorded, 0.2 still in effect
  const std::vector<ActuatorSample> late = {answer(998, 2, 0.4f)};  // nothing until step 2
  EXPECT_EQ(compare_actuators(s, rec, late, 0).missing, 2u);
}

}  // namespace
}  // namespace hitl::replay
