// `inspect --tui` with --expect on a busy link: the rows that fail their expectation come first,
// and what does not fit is counted ("+N more"), never dropped silently (issue 18).
#include <gtest/gtest.h>

#include "tui/inspect_dashboard.h"
#include "tui/memory_screen.h"
#include "tui/render.h"

namespace hitl::tui {
namespace {

telemetry::MessageSummary message(const std::string& name, double rate_hz) {
  telemetry::MessageSummary m;
  m.name = name;
  m.count = 1000;
  m.rate_hz = rate_hz;
  m.recent_rate_hz = rate_hz;
  return m;
}

TEST(InspectPaths, FailingExpectationsFirstAndTheRestCounted) {
  InspectDashboard dash("0.0.0.0:14570", {{"ODOMETRY", 250.0}, {"HIGHRES_IMU", 50.0}, {"VISION_SPEED", 30.0}}, false);
  telemetry::TrafficSummary s;
  s.duration_s = 10;
  s.frames = 30000;
  for (int i = 0; i < 24; ++i) s.messages.push_back(message("MSG_" + std::to_string(i), 10.0));
  s.messages.push_back(message("HIGHRES_IMU", 50.0));  // holds its expectation
  s.messages.push_back(message("ODOMETRY", 120.0));    // fails it; last by id
  dash.on_tick(s);                                     // VISION_SPEED: expected, never seen
  const DashboardModel m = dash.collect();
  ASSERT_GE(m.paths.rows.size(), 3u);
  EXPECT_EQ(m.paths.rows[0].name, "ODOMETRY");
  EXPECT_EQ(m.paths.rows[1].name, "VISION_SPEED");
  EXPECT_EQ(m.paths.rows[0].health, Health::Bad);
  EXPECT_EQ(m.paths.rows[2].name, "MSG_0");  // then the rest in their order

  MemoryScreen screen(80, 24);
  render(screen, m, {});
  SCOPED_TRACE(screen.dump());
  EXPECT_GE(screen.find("ODOMETRY").second, 0);
  EXPECT_GE(screen.find("VISION_SPEED").second, 0);
  const auto more = screen.find(" more");
  ASSERT_GE(more.second, 0);
  EXPECT_NE(screen.row(more.second).find("+"), std::string::npos) << screen.dump();
}

}  // namespace
}  // namespace hitl::tui
