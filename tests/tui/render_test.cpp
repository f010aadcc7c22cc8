// The dashboard drawn from fixed models onto the in-memory screen: text at its place, colours by
// health, "n/a" reasons, bars, at 80x24 and 200x60, too small and resized. The interaction (the
// messages scrolled back, the last key, the footer, the overlays) is in render_interaction_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/tui/render_screen.h"
#include "tests/tui/sample_model.h"
#include "tui/collect.h"
#include "tui/draw.h"
#include "tui/keys.h"
#include "tui/panels.h"
#include "tui/layout.h"
#include "tui/memory_screen.h"
#include "tui/message_log.h"
#include "tui/ncurses_screen.h"
#include "tui/render.h"

namespace hitl::tui {
namespace {

using test::draw;
using test::style_of;

TEST(Render, EveryPanelAt80x24) {
  const auto s = draw(80, 24, test::sample_model());
  SCOPED_TRACE(s.dump());
  EXPECT_EQ(s.find("hitl sim").second, 0);
  for (const char* title : {"Data paths", "dsp_hitl", "Vehicle", "EKF", "Messages", "Link 127.0.0.1:14560"})
    EXPECT_GE(s.find(title).second, 1) << title;
  // Compact two-column layout: data paths top left, vehicle top right, both on row 1.
  EXPECT_EQ(s.find("Data paths"), std::make_pair(2, 1));
  EXPECT_EQ(s.find("Vehicle"), std::make_pair(42, 1));
  // Key hints on the last row.
  EXPECT_NE(s.row(23).find("a:arm"), std::string::npos);
  EXPECT_NE(s.row(23).find("q:quit"), std::string::npos);
  // The IMU row: expected, measured, jitter, health word.
  const auto [x, y] = s.find("IMU ");
  ASSERT_GE(y, 0);
  EXPECT_NE(s.row(y).find("250.0  249.0  0.05"), std::string::npos) << s.row(y);
  EXPECT_NE(s.row(y).find(" ok"), std::string::npos);
  // Nothing of the left column spills into the right one.
  for (int row = 1; row < 23; ++row) EXPECT_EQ(s.at(39, row) == '|' || s.at(39, row) == '+' || s.at(39, row) == '-', true) << row;
}

TEST(Render, HealthColoursAndWords) {
  const auto s = draw(80, 24, test::sample_model());
  EXPECT_EQ(style_of(s, "IMU", "249.0").color, Color::Good);
  EXPECT_EQ(style_of(s, "mag", "45.0").color, Color::Warning);
  EXPECT_EQ(style_of(s, "baro", "5.0").color, Color::Bad);
  EXPECT_EQ(style_of(s, "mag", "warn").color, Color::Warning);
  EXPECT_EQ(style_of(s, "baro", "bad").color, Color::Bad);
  // dsp_hitl: the stalled BARO counter carries a red STOP.
  EXPECT_EQ(style_of(s, "BARO pub", "STOP").color, Color::Bad);
  // EKF: test ratio 1.3 is rejected (red), 0.7 marginal (yellow), 0.2 fine (green).
  EXPECT_EQ(style_of(s, "pos v", "1.30").color, Color::Bad);
  EXPECT_EQ(style_of(s, "pos h", "0.70").color, Color::Warning);
  EXPECT_EQ(style_of(s, "vel", "0.20").color, Color::Good);
  // A GPS glitch is a fault: red, and first; a valid flag green; what does not fit is counted.
  const auto glitch = s.find("GPS glitch");
  const auto att = s.find("attitude");
  EXPECT_EQ(s.style_at(glitch.first, glitch.second).color, Color::Bad);
  EXPECT_EQ(s.style_at(att.first, att.second).color, Color::Good);
  EXPECT_EQ(glitch.second, att.second);
  EXPECT_LT(glitch.first, att.first);
  EXPECT_GE(s.find("+1").second, 0);
  EXPECT_GE(s.find("vs truth 0.12 m h, -0.03 m v, 0.4 deg").second, 0);
  // The last message is an error.
  EXPECT_EQ(style_of(s, "9.0", "Preflight Fail").color, Color::Bad);
}

TEST(Render, ThresholdsFromTheSessionsPaths) {
  // 5 % and 20 % from an expected 100 Hz; a stream that went quiet is red whatever its rate.
  std::vector<hil::DataPathStats> in;
  auto add = [&](const char* name, double rate_hz, double since_last_s) {
    hil::DataPathStats p;
    p.name = name;
    p.expected_hz = 100;
    p.stats.rate_hz = rate_hz;
    p.stats.count = 100;
    p.stats.since_last_s = since_last_s;
    in.push_back(p);
  };
  add("a", 95.0, 0.01);
  add("b", 105.0, 0.01);
  add("c", 94.9, 0.01);
  add("d", 80.0, 0.01);
  add("e", 79.9, 0.01);
  add("f", 100.0, 2.0);   // stale
  add("g", 100.0, -1.0);  // never
  const auto panel = paths_from(in, false, "");
  ASSERT_EQ(panel.rows.size(), 7u);
  EXPECT_EQ(panel.rows[0].health, Health::Good);
  EXPECT_EQ(panel.rows[1].health, Health::Good);
  EXPECT_EQ(panel.rows[2].health, Health::Degraded);
  EXPECT_EQ(panel.rows[3].health, Health::Degraded);
  EXPECT_EQ(panel.rows[4].health, Health::Bad);
  EXPECT_EQ(panel.rows[5].health, Health::Bad);
  EXPECT_EQ(panel.rows[5].note, "stale");
  EXPECT_EQ(panel.rows[6].health, Health::Bad);
  // Paused: not judged, the note says why.
  EXPECT_EQ(paths_from(in, true, "").rows[4].note, "pause");
  auto m = test::sample_model();
  m.paths = panel;
  const auto s = draw(80, 24, m);
  EXPECT_EQ(style_of(s, "e ", "79.9").color, Color::Bad);
  EXPECT_NE(s.dump().find("stale"), std::string::npos);
}

TEST(Render, UnavailablePanelsSayWhy) {
  auto m = test::sample_model();
  m.dsp_hitl = DspHitlPanel{};
  m.dsp_hitl->unavailable = "no dsp_hitl on this board (nsh: qshell: command not found)";
  m.ekf = EkfPanel{};
  m.ekf->unavailable = "waiting for an autopilot HEARTBEAT through udp:127.0.0.1:14600";
  const auto s = draw(80, 24, m);
  SCOPED_TRACE(s.dump());
  const auto [tx, ty] = s.find("dsp_hitl");
  const auto [x, y] = s.find("n/a: no dsp_hitl on this board");
  EXPECT_EQ(x, 1);       // inside the box, first column
  EXPECT_EQ(y, ty + 1);  // first row under the title
  EXPECT_EQ(s.style_at(x, y).color, Color::Dim);
  EXPECT_GE(s.find("n/a: waiting for an autopilot").second, 0);
}

TEST(Render, MotorBarsAreProportional) {
  const auto s = draw(80, 24, test::sample_model());
  auto bar_of = [&](const char* label) {
    const auto [x, y] = s.find(label);
    EXPECT_GE(y, 0) << label;
    std::string cells;
    for (int i = x + 3; s.at(i, y) == '#' || s.at(i, y) == '-'; ++i) cells += s.at(i, y);
    return cells;
  };
  const std::string m1 = bar_of("M0 "), m2 = bar_of("M1 "), m3 = bar_of("M2 "), m4 = bar_of("M3 ");
  ASSERT_GT(m1.size(), 10u);
  EXPECT_EQ(m1.size(), m3.size());
  const auto filled = [](const std::string& b) { return static_cast<long>(std::count(b.begin(), b.end(), '#')); };
  EXPECT_EQ(filled(m1), std::lround(0.5 * static_cast<double>(m1.size())));
  EXPECT_EQ(filled(m2), std::lround(0.25 * static_cast<double>(m2.size())));
  EXPECT_EQ(filled(m3), static_cast<long>(m3.size()));
  EXPECT_EQ(filled(m4), 0);
  EXPECT_EQ(s.style_at(s.find("M0 ").first + 3, s.find("M0 ").second).color, Color::Accent);
  EXPECT_NE(s.row(s.find("M0 ").second).find("0.50"), std::string::npos);
  EXPECT_NE(s.row(s.find("M0 ").second).find("500 rad/s"), std::string::npos);
}

TEST(Render, BarsAndNumbersNeverShowANaNAsAValue) {
  EXPECT_EQ(bar(NAN, 5), "?????");
  EXPECT_EQ(bar(2.0, 4), "####");
  EXPECT_EQ(bar(-1.0, 4), "----");
  EXPECT_EQ(number(NAN, 2), "n/a");
  EXPECT_EQ(number(std::nullopt, 2), "n/a");
  auto m = test::sample_model();
  m.ekf->ratios[0].value = NAN;
  m.paths.rows[0].rate_hz = NAN;
  const auto s = draw(80, 24, m);
  EXPECT_NE(s.dump().find("???"), std::string::npos);
  EXPECT_NE(s.row(s.find("IMU ").second).find("n/a"), std::string::npos);
}

TEST(Render, WideAndTallAt200x60) {
  const auto m = test::sample_model();
  const auto s = draw(200, 60, m);
  SCOPED_TRACE(s.dump());
  const auto l = layout_for(200, 60, m);
  // Messages use the height there is (issue 18: the EKF was stretched over 20 blank rows while
  // messages had 6): down the right column under the EKF, to the footer.
  EXPECT_EQ(l.messages.x, 100);
  EXPECT_EQ(l.messages.y, l.ekf.y + l.ekf.h);
  EXPECT_EQ(l.messages.y + l.messages.h, 59);
  EXPECT_EQ(l.link.y + l.link.h, 59);
  EXPECT_EQ(s.find("Messages").first, 102);
  EXPECT_EQ(s.find("Messages").second, l.messages.y);
  // All nine messages fit now, oldest first.
  EXPECT_LT(s.find("line 0").second, s.find("Preflight Fail").second);
  // Wide panels: the message name, max gap and count columns; the status text's own dsp_hitl
  // labels; a second bar for rotor speed; the link's fields three a line.
  const int imu_y = s.find("IMU ").second;
  EXPECT_NE(s.row(imu_y).find("HIL_SENSOR"), std::string::npos) << s.row(imu_y);
  EXPECT_NE(s.row(imu_y).find("12345"), std::string::npos);
  EXPECT_GE(s.find("HIL sensor_imu received").second, 0);
  EXPECT_GE(s.find("polled 0.4 s ago").second, 0);
  const int m1_y = s.find("M0 ").second;
  const std::string m1 = s.row(m1_y);
  EXPECT_EQ(std::count(m1.begin(), m1.end(), '#') > 20, true) << m1;  // command bar + rotor bar
  EXPECT_EQ(s.find("late 3").second, s.find("out 1000").second);  // three fields a line
  EXPECT_EQ(s.find("in 900").second, s.find("out 1000").second + 1);
}

// A bridge's link names are shown whole when the panel has room (issue 18: they were cut to 8).
TEST(Render, LongPathNamesAreShownWholeWhenThereIsRoom) {
  auto m = test::sample_model();
  m.paths.rows.push_back(test::path("tx udp:127.0.0.1:14550", "to 127.0.0.1:14550", 0, 50.0, Health::Good));
  const auto s = draw(200, 60, m);
  SCOPED_TRACE(s.dump());
  EXPECT_GE(s.find("tx udp:127.0.0.1:14550").second, 0);
}


TEST(Render, MonochromeTerminalsStillTellTheGradesApart) {
  const Style good{Color::Good, false, false}, warn{Color::Warning, false, false}, bad{Color::Bad, false, false};
  // Without colours: plain, bold, bold standout.
  const auto g = curses_look(good, false), w = curses_look(warn, false), b = curses_look(bad, false);
  EXPECT_EQ(g.pair, 0);
  EXPECT_EQ(w.pair, 0);
  EXPECT_EQ(b.pair, 0);
  EXPECT_NE(g.attributes, w.attributes);
  EXPECT_NE(w.attributes, b.attributes);
  EXPECT_NE(g.attributes, b.attributes);
  // With colours: a pair each.
  EXPECT_NE(curses_look(good, true).pair, curses_look(warn, true).pair);
  EXPECT_NE(curses_look(warn, true).pair, curses_look(bad, true).pair);
  EXPECT_EQ(curses_look(Style{}, true).pair, 0);
}

TEST(Render, TooSmallSaysSo) {
  const auto s = draw(60, 20, test::sample_model());
  EXPECT_NE(s.row(0).find("needs 80x24"), std::string::npos) << s.dump();
}

TEST(Render, ResizeRedrawsForTheNewSize) {
  const auto m = test::sample_model();
  const auto small = layout_for(80, 24, m);
  const auto big = layout_for(120, 40, m);
  EXPECT_FALSE(small.too_small);
  EXPECT_EQ(small.messages.x, 40);  // right column
  EXPECT_EQ(big.messages.x, 60);    // down the right column: more rows than across the bottom
  EXPECT_GE(big.messages.h, 20);
  EXPECT_GT(big.messages.h, small.messages.h);
  // A left column shorter than the right one (no dsp_hitl): messages across the bottom.
  auto no_dsp = m;
  no_dsp.dsp_hitl.reset();
  no_dsp.paths.rows.resize(1);
  const auto bottom = layout_for(120, 60, no_dsp);
  EXPECT_EQ(bottom.messages.x, 0);
  EXPECT_EQ(bottom.messages.w, 120);
  // Panels never overlap and stay on screen.
  for (const auto& l : {small, big}) {
    const Rect panels[] = {l.paths, l.dsp_hitl, l.link, l.vehicle, l.ekf, l.messages};
    for (const auto& a : panels) {
      EXPECT_GE(a.y, 1);
      EXPECT_LE(a.x + a.w, l.footer.w);
      EXPECT_LE(a.y + a.h, l.footer.y);
      for (const auto& b : panels) {
        if (&a == &b || a.empty() || b.empty()) continue;
        const bool apart = a.x + a.w <= b.x || b.x + b.w <= a.x || a.y + a.h <= b.y || b.y + b.h <= a.y;
        EXPECT_TRUE(apart);
      }
    }
  }
}

TEST(Render, InspectHasPathsLinkAndMessagesOnly) {
  DashboardModel m;
  m.title = "hitl inspect";
  m.state = "receiving";
  m.paths.rows = {test::path("ODOMETRY", "ODOMETRY", 250, 249.8, Health::Good)};
  m.link_partner = "0.0.0.0:14570";
  m.link = {{"frames", "2500"}};
  m.messages = {{0.5, Severity::Warning, "[127.0.0.1:14561 1] low battery"}};
  const auto s = draw(80, 24, m);
  SCOPED_TRACE(s.dump());
  EXPECT_EQ(s.find("Data paths").second, 1);
  EXPECT_EQ(s.find("Vehicle").second, -1);
  EXPECT_EQ(s.find("dsp_hitl").second, -1);
  EXPECT_GT(s.find("Link 0.0.0.0:14570").second, 1);
  EXPECT_GT(s.find("low battery").second, s.find("Link").second);
  EXPECT_NE(s.row(23).find("?:help q:quit"), std::string::npos);
  EXPECT_EQ(s.row(23).find("a:arm"), std::string::npos);  // inspect has no actions
}

}  // namespace
}  // namespace hitl::tui

namespace hitl::tui {
namespace {

LatencyPanel sample_latency() {
  LatencyPanel p;
  p.matched = "by echo";
  p.count = 11501;
  p.p50_us = 20;
  p.p95_us = 50;
  p.p99_us = 5000;  // above the 4 ms step: yellow
  p.max_us = 10730;
  p.limit_us = 4000;
  for (const char* label : {"<250 us", "<500 us", "<1 ms", "<2 ms", "<4 ms", "<8 ms", "<16 ms", ">=16 ms"}) p.bins.push_back({label, 0});
  p.bins[0].count = 11000;
  p.bins[2].count = 400;
  p.bins[5].count = 101;
  return p;
}

TEST(RenderLatency, APanelOfItsOwnOnTallTerminalsOnlyInSpareRows) {
  auto model = test::sample_model();
  model.latency = sample_latency();
  const auto tall = draw(200, 60, model);
  SCOPED_TRACE(tall.dump());
  const auto [x, y] = tall.find("Loop latency (by echo)");
  ASSERT_GE(y, 1);
  EXPECT_NE(tall.row(y + 1).find("p50 0.02  p95 0.05  p99 5.00  max 10.73 ms  n 11501"), std::string::npos);
  EXPECT_EQ(style_of(tall, "p95 0.05", "p99 5.00").color, Color::Warning);
  EXPECT_NE(tall.row(y + 2).find("<250 us"), std::string::npos);
  EXPECT_NE(tall.row(y + 2).find("11000"), std::string::npos);
  EXPECT_NE(tall.row(y + 4).find("<1 ms"), std::string::npos);  // empty bins between stay, as rows
  EXPECT_NE(tall.row(y + 7).find("<8 ms"), std::string::npos);
  EXPECT_EQ(tall.find(">=16 ms").second, -1);  // nothing after the last bin with samples
  // The other panels where they were without it.
  auto without = test::sample_model();
  const auto before = draw(200, 60, without);
  for (const char* title : {"Data paths", "Vehicle", "EKF", "Messages", "Link 127.0.0.1:14560"})
    EXPECT_EQ(tall.find(title), before.find(title)) << title;
  // 80x24 has no spare rows: the Link panel's fields say it.
  EXPECT_EQ(draw(80, 24, model).find("Loop latency").second, -1);
}

}  // namespace
}  // namespace hitl::tui
