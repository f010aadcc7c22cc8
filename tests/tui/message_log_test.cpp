// The messages panel's stamps: seconds since the start, or the clock the dashboard gives it (the sim
// dashboard: simulated time, so the header, the messages and a reset's own text agree).
#include <gtest/gtest.h>

#include "tui/message_log.h"

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
