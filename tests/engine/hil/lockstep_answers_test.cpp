// Lockstep answers matched by time (issue 20): an answer counts for the HIL_SENSOR whose time_usec
// it echoes; answers to earlier ones are late, counted and ignored; a stack on its own clock (no
// echo) is taken as before.
#include <gtest/gtest.h>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "engine/hil/actuator_input.h"

namespace hitl::hil {
namespace {

mavlink::msg::HilActuatorControls answer(uint64_t time_usec, float u) {
  mavlink::msg::HilActuatorControls a;
  a.time_usec = time_usec;
  a.controls = {};
  for (std::size_t i = 0; i < 4; ++i) a.controls[i] = u;
  a.mode = mavlink::mode_flag::kSafetyArmed;
  return a;
}

TEST(LockstepAnswers, OnlyTheEchoOfTheLastSensorCounts) {
  ActuatorInput in(0.5);
  in.expect_answer_to(8000);
  EXPECT_TRUE(in.on_message(answer(8000, 0.3f), 1, 0.0));
  EXPECT_EQ(in.take_new(), 1u);
  in.expect_answer_to(12000);
  // A second answer to 8000 arrives after 12000 went out: late, ignored (controls and step).
  EXPECT_FALSE(in.on_message(answer(8000, 0.9f), 1, 0.001));
  EXPECT_EQ(in.take_new(), 0u);
  EXPECT_EQ(in.counters().late, 1u);
  EXPECT_FLOAT_EQ(static_cast<float>(in.commands(0.001).u[0]), 0.3f);
  EXPECT_EQ(in.take_heard(), 2u);  // but the stack is alive
  EXPECT_TRUE(in.on_message(answer(12000, 0.4f), 1, 0.002));
  EXPECT_EQ(in.take_new(), 1u);
  EXPECT_FLOAT_EQ(static_cast<float>(in.commands(0.002).u[0]), 0.4f);
  EXPECT_EQ(in.counters().foreign_clock, 0u);
}

TEST(LockstepAnswers, AStackOnItsOwnClockIsTakenAsBefore) {
  ActuatorInput in(0.5);
  in.expect_answer_to(4000);
  EXPECT_TRUE(in.on_message(answer(0, 0.2f), 1, 0.0));  // before anything was sent: not an echo
  EXPECT_EQ(in.take_new(), 1u);
  in.expect_answer_to(4000000);
  EXPECT_TRUE(in.on_message(answer(0, 0.2f), 1, 0.0));  // no echo (time_usec 0)
  EXPECT_TRUE(in.on_message(answer(90000000000ull, 0.2f), 1, 0.0));  // far ahead: an earlier session's clock
  EXPECT_EQ(in.take_new(), 2u);
  EXPECT_EQ(in.counters().foreign_clock, 3u);
  EXPECT_EQ(in.counters().late, 0u);
  EXPECT_GT(in.last_echo_offset_us(), 1000000);
}

TEST(LockstepAnswers, WithoutLockstepEveryAnswerCounts) {
  ActuatorInput in(0.5);
  EXPECT_TRUE(in.on_message(answer(1, 0.2f), 1, 0.0));
  EXPECT_TRUE(in.on_message(answer(0, 0.2f), 1, 0.0));
  EXPECT_EQ(in.take_new(), 2u);
  EXPECT_EQ(in.counters().late, 0u);
}

}  // namespace
}  // namespace hitl::hil
