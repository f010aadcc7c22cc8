#include "target/core/periodic_schedule.h"

#include <gtest/gtest.h>

namespace hitl::target {
namespace {

TEST(PeriodicSchedule, NotDueUntilStarted) {
  PeriodicSchedule s(4000);
  EXPECT_FALSE(s.due(0));
  EXPECT_FALSE(s.due(1000000));
}

TEST(PeriodicSchedule, StaysOnItsGridDespiteLatePolls) {
  PeriodicSchedule s(4000);
  s.start(1000);
  EXPECT_TRUE(s.due(1000));
  s.consume(1000);
  EXPECT_FALSE(s.due(4999));
  EXPECT_TRUE(s.due(5700));  // polled 700 us late
  s.consume(5700);
  EXPECT_EQ(s.next_due_us(), 9000U);  // the grid, not 5700 + 4000
  EXPECT_EQ(s.resyncs(), 0U);
}

TEST(PeriodicSchedule, ReanchorsInsteadOfBursting) {
  PeriodicSchedule s(4000);
  s.start(0);
  s.consume(0);
  EXPECT_TRUE(s.due(50000));  // 12 periods late: one tick, then re-anchored
  s.consume(50000);
  EXPECT_EQ(s.next_due_us(), 54000U);
  EXPECT_FALSE(s.due(50001));
  EXPECT_EQ(s.resyncs(), 1U);
}

TEST(PeriodicSchedule, StopAndRestart) {
  PeriodicSchedule s(10000);
  s.start(0);
  s.stop();
  EXPECT_FALSE(s.due(20000));
  s.start(20000);
  EXPECT_TRUE(s.due(20000));
}

}  // namespace
}  // namespace hitl::target
