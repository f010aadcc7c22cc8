// The messages panel's stamps: seconds since the start, or the clock the dashboard gives it (the sim
// dashboard: simulated time, so the header, the messages and a reset's own text agree).
#include <gtest/gtest.h>

#include "tui/memory_screen.h"
#include "tui/message_log.h"
#include "tui/panels.h"

namespace hitl::tui {
namespace {

TEST(MessageLog, StampsWithTheGivenClock) {
  MessageLog log;
  log.add(Severity::Info, "before");
  double sim_s = 123.4;
  log.set_clock([&] { return sim_s; });
  log.add(Severity::Info, "at 123.4");
  sim_s = 130.0;
  log.add(Severity::Warning, "at 130\x07");
  const auto lines = log.lines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_LT(lines[0].t_s, 5.0);
  EXPECT_DOUBLE_EQ(lines[1].t_s, 123.4);
  EXPECT_DOUBLE_EQ(lines[2].t_s, 130.0);
  EXPECT_EQ(lines[2].text, "at 130 ");  // control bytes never reach the terminal
}

}  // namespace
}  // namespace hitl::tui

namespace hitl::tui {
namespace {

// Issue 18: PX4 repeats its preflight failures every few seconds; each shows once, with a count,
// moved to the bottom while it repeats within the window; another source or an older one is new.
TEST(MessageLog, AStatustextRepeatedWithinTheWindowShowsOnceWithACount) {
  double wall_s = 100.0;
  MessageLog log([&] { return wall_s; });
  log.add_statustext(Severity::Error, "autopilot", "Preflight Fail: ekf2 not aligned");
  log.add(Severity::Notice, "arm ...");
  wall_s += 2;
  log.add_statustext(Severity::Error, "autopilot", "Preflight Fail: ekf2 not aligned");
  wall_s += 2;
  log.add_statustext(Severity::Error, "autopilot", "Preflight Fail: ekf2 not aligned");
  log.add_statustext(Severity::Error, "board 2", "Preflight Fail: ekf2 not aligned");  // another source
  auto lines = log.lines();
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].text, "arm ...");
  EXPECT_EQ(lines[1].text, "Preflight Fail: ekf2 not aligned");
  EXPECT_EQ(lines[1].repeats, 3);
  EXPECT_EQ(lines[2].repeats, 1);
  // After a quiet window it is news again; the session's own lines are never collapsed.
  wall_s += MessageLog::kRepeatWindow_s + 1;
  log.add_statustext(Severity::Error, "autopilot", "Preflight Fail: ekf2 not aligned");
  log.add(Severity::Notice, "arm ...");
  lines = log.lines();
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[3].repeats, 1);
  EXPECT_EQ(lines[4].text, "arm ...");

  MemoryScreen s(80, 24);
  draw_messages(s, {0, 0, 80, 8}, log.lines());
  EXPECT_GE(s.find("Preflight Fail: ekf2 not aligned (x3)").second, 0) << s.dump();
}

}  // namespace
}  // namespace hitl::tui
