// The graphs' pure parts: series -> cells (braille and ASCII), the bounded history, the choice of
// symbols; and the graphs on the rendered dashboard: absent at 80x24, present at 200x60.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/tui/render_screen.h"
#include "tests/tui/sample_model.h"
#include "tui/graph.h"
#include "tui/graph_history.h"
#include "tui/layout.h"

namespace hitl::tui {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Graph, BrailleDotsAreUnicodesOrder) {
  // U+2801 dot 1 (top left), U+2808 dot 4 (top right), U+2840 dot 7, U+2880 dot 8 (bottom row).
  EXPECT_EQ(braille_bit(0, 0), 0x01u);
  EXPECT_EQ(braille_bit(1, 0), 0x08u);
  EXPECT_EQ(braille_bit(0, 3), 0x40u);
  EXPECT_EQ(braille_bit(1, 3), 0x80u);
  EXPECT_EQ(utf8(kBrailleBase + 0xFF), "\u28FF");
}

TEST(Graph, ResampleRightAlignsAPartWindow) {
  // Window of 4 samples on 4 columns, 2 samples so far: they are the newest, on the right.
  const auto c = resample({1.0, 2.0}, 4, 4);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_TRUE(std::isnan(c[0]));
  EXPECT_TRUE(std::isnan(c[1]));
  EXPECT_EQ(c[2], 1.0);
  EXPECT_EQ(c[3], 2.0);
  // 4 samples on 2 columns: means; a NaN is skipped.
  const auto m = resample({1.0, 3.0, kNaN, 5.0}, 4, 2);
  EXPECT_EQ(m[0], 2.0);
  EXPECT_EQ(m[1], 5.0);
}

TEST(Graph, ARampDrawsTheExpectedBrailleCells) {
  // One cell high (4 dot rows), 2 cells wide (4 dot columns), range 0..3: the ramp 0,1,2,3 puts
  // one dot a column, one dot row higher each: bottom-left and row 2 right in the first cell, row 1
  // left and top-right in the second.
  const auto rows = plot({0, 1, 2, 3}, 4, 2, 1, 0, 3, GraphSymbols::Braille);
  ASSERT_EQ(rows.size(), 1u);
  ASSERT_EQ(rows[0].size(), 2u);
  EXPECT_EQ(rows[0][0], kBrailleBase + (braille_bit(0, 3) | braille_bit(1, 2)));  // U+2860
  EXPECT_EQ(rows[0][1], kBrailleBase + (braille_bit(0, 1) | braille_bit(1, 0)));  // U+280A
  EXPECT_EQ(utf8(rows[0][0]) + utf8(rows[0][1]), "\u2860\u280A");
}

TEST(Graph, AStepIsJoinedByVerticalDots) {
  // 0 then 7 over two cells high (8 dot rows): the second column fills dot rows 1..7.
  const auto rows = plot({0, 7}, 2, 1, 2, 0, 7, GraphSymbols::Braille);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0][0], kBrailleBase + (braille_bit(1, 0) | braille_bit(1, 1) | braille_bit(1, 2) | braille_bit(1, 3)));
  EXPECT_EQ(rows[1][0], kBrailleBase + (braille_bit(0, 3) | braille_bit(1, 0) | braille_bit(1, 1) | braille_bit(1, 2)));
}

TEST(Graph, AsciiFallbackMarksThreeHeightsACell) {
  // One cell per sample, 2 rows = 6 levels over 0..5.
  const auto rows = plot({0, 1, 2, 3, 4, 5, kNaN}, 7, 7, 2, 0, 5, GraphSymbols::Ascii);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], U"   _-' ");
  EXPECT_EQ(rows[1], U"_-'    ");
  for (const auto& r : rows)
    for (char32_t c : r) EXPECT_LT(c, 0x80u);
}

TEST(Graph, ValuesOutsideTheRangeAreClampedAndNaNLeavesAGap) {
  const auto rows = plot({-100, kNaN, 100}, 3, 3, 1, 0, 1, GraphSymbols::Ascii);
  EXPECT_EQ(rows[0], U"_ '");
}

TEST(Graph, OverlayMergesBrailleDots) {
  std::vector<std::u32string> a = {std::u32string(1, kBrailleBase + 0x01) + U" "};
  const std::vector<std::u32string> b = {std::u32string(1, kBrailleBase + 0x80) + U"_"};
  overlay(a, b);
  EXPECT_EQ(a[0][0], kBrailleBase + 0x81);
  EXPECT_EQ(a[0][1], U'_');
}

TEST(Graph, RangeWidensAFlatSeries) {
  const auto [lo, hi] = range_of({{5.0, 5.0, kNaN}}, 2.0);
  EXPECT_EQ(lo, 4.0);
  EXPECT_EQ(hi, 6.0);
  EXPECT_EQ(range_of({{kNaN}}, 1.0), (std::pair{0.0, 1.0}));
}

TEST(Graph, SymbolsFollowTheLocaleUnlessTheUserSays) {
  EXPECT_EQ(choose_graph_symbols(nullptr, true, "xterm-256color"), GraphSymbols::Braille);
  EXPECT_EQ(choose_graph_symbols(nullptr, false, "xterm-256color"), GraphSymbols::Ascii);
  EXPECT_EQ(choose_graph_symbols(nullptr, true, "linux"), GraphSymbols::Ascii);  // the Linux console
  EXPECT_EQ(choose_graph_symbols(nullptr, true, nullptr), GraphSymbols::Braille);
  EXPECT_EQ(choose_graph_symbols("ascii", true, "tmux-256color"), GraphSymbols::Ascii);
  EXPECT_EQ(choose_graph_symbols("braille", false, "linux"), GraphSymbols::Braille);
  EXPECT_EQ(choose_graph_symbols("nonsense", true, "tmux"), GraphSymbols::Braille);
}

TEST(GraphHistory, RingKeepsTheLastCapacityValues) {
  SampleRing ring(3);
  for (int i = 0; i < 10; ++i) ring.push(i);
  EXPECT_EQ(ring.values(), (std::vector<double>{7, 8, 9}));
  EXPECT_EQ(ring.size(), 3u);
}

TEST(GraphHistory, SamplesAtItsRateAndStaysBounded) {
  GraphHistory h(60, 10);  // 600 samples
  auto m = test::sample_model();
  m.vehicle->truth_altitude_m = 2.0;
  m.vehicle->altitude_m = 1.9;
  h.add(0.0, m, std::nullopt);
  h.add(0.05, m, std::nullopt);  // within the period: not sampled
  EXPECT_EQ(h.panel().truth_altitude_m.size(), 1u);
  for (int i = 1; i < 2000; ++i) h.add(i * 0.1, m, i > 1990 ? std::optional<double>(0.5) : std::nullopt);
  const auto p = h.panel();
  EXPECT_EQ(p.capacity, 600u);
  EXPECT_EQ(p.truth_altitude_m.size(), 600u);
  EXPECT_EQ(p.estimate_altitude_m.back(), 1.9);
  ASSERT_EQ(p.rates.size(), m.paths.rows.size());
  EXPECT_EQ(p.rates[0].name, "IMU");
  EXPECT_EQ(p.rates[0].expected_hz, 250);
  EXPECT_EQ(p.rates[0].rate_hz.size(), 600u);
  EXPECT_EQ(p.tracking_error_m.back(), 0.5);
}

TEST(GraphHistory, OnSimulatedTimeAPausedSessionAddsNothingAndAFastOneFillsEveryPeriod) {
  // The dashboard samples on the session's simulated clock: paused, the graphs hold still; at
  // --speed 5 a frame 0.5 s of simulated time later holds five samples of its values, so the
  // axis is simulated seconds at any speed.
  GraphHistory h(60, 10);
  auto m = test::sample_model();
  m.vehicle->truth_altitude_m = 1.0;
  h.add(9.995, m, std::nullopt);
  h.add(10.094, m, std::nullopt);  // a hair early: sampled, and the next one is due at 10.195
  for (int frame = 0; frame < 50; ++frame) h.add(10.094, m, std::nullopt);  // paused
  EXPECT_EQ(h.panel().truth_altitude_m.size(), 2u);
  m.vehicle->truth_altitude_m = 2.0;
  h.add(10.595, m, std::nullopt);
  EXPECT_EQ(h.panel().truth_altitude_m, (std::vector<double>{1, 1, 2, 2, 2, 2, 2}));
  h.add(1000.0, m, std::nullopt);  // far ahead: one window of it, no more
  EXPECT_EQ(h.panel().truth_altitude_m.size(), 600u);
  m.vehicle->truth_altitude_m = 3.0;
  h.add(5.0, m, std::nullopt);  // a clock that went back (a new session): sampled, and goes on from there
  h.add(5.1, m, std::nullopt);
  EXPECT_EQ(h.panel().truth_altitude_m.back(), 3.0);
  EXPECT_EQ(h.panel().truth_altitude_m[597], 2.0);
}

TEST(GraphHistory, NoTrackingErrorInTheWindowMeansNoTrackingGraph) {
  GraphHistory h(1, 10);
  const auto m = test::sample_model();
  h.add(0, m, 0.3);
  for (int i = 1; i <= 10; ++i) h.add(i * 0.1, m, std::nullopt);
  EXPECT_TRUE(h.panel().tracking_error_m.empty());
}

DashboardModel model_with_graphs(bool tracking) {
  auto m = test::sample_model();
  GraphHistory h(60, 10);
  for (int i = 0; i < 600; ++i) {
    m.vehicle->truth_altitude_m = i / 60.0;  // a climb to 10 m
    m.vehicle->altitude_m = i / 60.0 - 0.2;
    h.add(i * 0.1, m, tracking ? std::optional<double>(0.3) : std::nullopt);
  }
  m.graphs = h.panel();
  return m;
}

TEST(GraphsRender, NotAt80x24) {
  const auto with = model_with_graphs(true);
  auto plain = with;
  plain.graphs.reset();
  const auto a = test::draw(80, 24, plain), b = test::draw(80, 24, with);
  EXPECT_EQ(a.dump(), b.dump());
  EXPECT_TRUE(layout_for(80, 24, with).graphs.empty());
}

TEST(GraphsRender, At200x60BrailleUnderTheLink) {
  const auto m = model_with_graphs(true);
  const auto s = test::draw(200, 60, m);
  SCOPED_TRACE(s.dump());
  const auto l = layout_for(200, 60, m);
  ASSERT_FALSE(l.graphs.empty());
  EXPECT_EQ(l.graphs.y, l.link.y + l.link.h);
  EXPECT_EQ(l.graphs.y + l.graphs.h, 59);
  EXPECT_GE(s.find("Graphs, last 60 s").second, 0);
  const int alt_y = s.find("Altitude m: truth 10.0").second;
  ASSERT_GE(alt_y, 0);
  EXPECT_GE(s.find("Tracking error m: now 0.30").second, alt_y);
  EXPECT_GE(s.find("Rates Hz").second, 0);
  // Braille cells in the graph rows, and only braille or blanks there.
  int braille = 0;
  for (int y = l.graphs.y + 1; y < l.graphs.y + l.graphs.h - 1; ++y)
    for (int x = l.graphs.x + 1; x < l.graphs.x + l.graphs.w - 1; ++x) {
      const char32_t c = s.glyph_at(x, y);
      if (c >= kBrailleBase && c <= kBrailleBase + 0xFF) ++braille;
    }
  EXPECT_GT(braille, 100);
  // The IMU's rate row: its name, a graph at 249/250 (a steady line), its figures.
  const int rates_y = s.find("Rates Hz").second;
  int imu_y = -1;
  for (int y = rates_y; y < 60 && imu_y < 0; ++y)
    if (s.row(y).substr(1, 4) == "IMU ") imu_y = y;
  ASSERT_GT(imu_y, alt_y);
  EXPECT_NE(s.row(imu_y).find("249.0/250.0 Hz"), std::string::npos) << s.row_utf8(imu_y);
  // 249 of 312.5 at the top: dot row 1 of 4 from the top -> dots 2 and 5 in every full cell.
  EXPECT_EQ(s.glyph_at(l.graphs.x + 1 + 9 + 5, imu_y), kBrailleBase + (braille_bit(0, 1) | braille_bit(1, 1)));
  // The other panels are where they were without graphs (messages, vehicle, ekf).
  const auto plain = layout_for(200, 60, test::sample_model());
  EXPECT_EQ(l.messages.x, plain.messages.x);
  EXPECT_EQ(l.messages.y, plain.messages.y);
  EXPECT_EQ(l.link.y, plain.link.y);
}

TEST(GraphsRender, AsciiFallbackHasNoWideCells) {
  const auto m = model_with_graphs(false);
  MemoryScreen s(200, 60, GraphSymbols::Ascii);
  render(s, m, {});
  SCOPED_TRACE(s.dump());
  EXPECT_GE(s.find("Graphs, last 60 s").second, 0);
  EXPECT_LT(s.find("Tracking error").second, 0);  // no trajectory in the window
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 200; ++x) EXPECT_LT(s.glyph_at(x, y), 0x80u);
  const auto l = layout_for(200, 60, m);
  int marks = 0;
  for (int y = l.graphs.y + 2; y < l.graphs.y + l.graphs.h - 1; ++y)
    for (int x = l.graphs.x + 1; x < l.graphs.x + l.graphs.w - 1; ++x) marks += s.at(x, y) == '\'' || s.at(x, y) == '_';
  EXPECT_GT(marks, 50);
}

TEST(GraphsRender, BesideMessagesAcrossTheBottom) {
  auto m = model_with_graphs(false);
  m.dsp_hitl.reset();
  m.paths.rows.resize(1);
  m.graphs->rates.resize(1);
  const auto l = layout_for(200, 60, m);
  ASSERT_FALSE(l.graphs.empty());
  EXPECT_LE(l.graphs.x + l.graphs.w, l.messages.x);
  EXPECT_EQ(l.graphs.y, l.messages.y);
  EXPECT_EQ(l.messages.x + l.messages.w, 200);
}

}  // namespace
}  // namespace hitl::tui
