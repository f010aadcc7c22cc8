// The doctor's simulator checks (engine/doctor/simulator_checks) on fixed inputs: the session found,
// paused, its pace and its late ticks.
#include <gtest/gtest.h>

#include "engine/doctor/simulator_checks.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

TEST(DoctorSimulator, SessionPausedPaceLateTicks) {
  SessionStatus none;
  EXPECT_EQ(session_check(none, 14600, false).result, Verdict::Fail);
  EXPECT_EQ(session_check(none, 14600, true).result, Verdict::Warn);
  EXPECT_EQ(session_check(none, 14600, std::nullopt).result, Verdict::Fail);
  EXPECT_EQ(paused_check(none).result, Verdict::Skip);
  auto s = session(true, 5, 1250, 15, 0);
  EXPECT_EQ(session_check(s, 14600, true).result, Verdict::Pass);
  EXPECT_EQ(paused_check(s).result, Verdict::Pass);
  s.paused = true;
  EXPECT_EQ(paused_check(s).result, Verdict::Fail);
  s = session(false, 0.6, 200, 15, 0);
  s.speed = 1.0;
  EXPECT_EQ(real_time_check(s).result, Verdict::Fail);
  s.lockstep = true;
  EXPECT_EQ(real_time_check(s).result, Verdict::Warn);
  s.speed = 0.0;
  EXPECT_EQ(real_time_check(s).result, Verdict::Pass);
  s = session(false, 1.0, 200, 15, 0);
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Skip);
  s.first_late = SessionStatus::LateSample{10.0, 3};
  s.last_late = SessionStatus::LateSample{12.0, 3};
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Pass);
  s.last_late = SessionStatus::LateSample{12.0, 10};
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Warn);  // 7 of 500
  s.last_late = SessionStatus::LateSample{12.0, 100};
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Fail);  // 97 of 500
  s.lockstep = true;
  EXPECT_EQ(late_ticks_check(s).result, Verdict::Warn);
}

TEST(DoctorSimulator, LoopLatencyWarnsWhenP99ExceedsOneStep) {
  SessionStatus none;
  EXPECT_EQ(loop_latency_check(none).result, Verdict::Skip);
  auto s = session(true, 5, 1250, 15, 0);
  s.lockstep = true;
  EXPECT_EQ(loop_latency_check(s).result, Verdict::Skip);  // an older session: no "sim_lat99"
  s.loop_latency_p99_us = -1;
  EXPECT_EQ(loop_latency_check(s).result, Verdict::Skip);  // nothing answered yet
  s.loop_latency_p99_us = 4000;                             // exactly one step
  EXPECT_EQ(loop_latency_check(s).result, Verdict::Pass);
  s.loop_latency_p99_us = 4001;
  const auto late = loop_latency_check(s);
  EXPECT_EQ(late.result, Verdict::Warn);
  EXPECT_NE(late.saw.find("p99 4.00 ms"), std::string::npos) << late.saw;
  EXPECT_FALSE(late.fix.empty());
  // Outside lockstep the next message of the board's 200 Hz stream, taken at the next 4 ms tick,
  // is the floor (9 ms): one step beyond it is the limit.
  s.lockstep = false;
  s.loop_latency_p99_us = 12000;
  EXPECT_EQ(loop_latency_check(s).result, Verdict::Pass);
  s.loop_latency_p99_us = 13500;
  EXPECT_EQ(loop_latency_check(s).result, Verdict::Warn);
}

}  // namespace
}  // namespace hitl::doctor
