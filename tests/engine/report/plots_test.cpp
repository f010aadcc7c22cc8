// Thinning for drawing, and which plots a log gets.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/report/html.h"
#include "engine/report/plots.h"

namespace hitl::report {
namespace {

std::vector<double> ramp(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<double>(i);
  return v;
}

TEST(Plots, ThinningKeepsEveryStrideThPointAndTheLast) {
  const auto x = ramp(10);
  const auto s = thinned("a", SeriesStyle::Plain, x, x, 4);  // stride 3: 0 3 6 9
  EXPECT_EQ(s.samples, 10u);
  EXPECT_EQ(s.x, (std::vector<double>{0, 3, 6, 9}));
  const auto t = thinned("b", SeriesStyle::Plain, ramp(11), ramp(11), 4);  // 0 3 6 9, then the last
  EXPECT_EQ(t.x, (std::vector<double>{0, 3, 6, 9, 10}));
  const auto all = thinned("c", SeriesStyle::Plain, x, x, 100);
  EXPECT_EQ(all.x.size(), 10u);
}

TEST(Plots, RepeatedPointsAreDrawnOnce) {
  const std::vector<double> x = {0, 1, 1, 2}, y = {5, 6, 6, 7};
  EXPECT_EQ(thinned("a", SeriesStyle::Plain, x, y, 100).x.size(), 3u);
}

TEST(Plots, OnlyPlotsWithDataAndTheTrackingRmsInTheNote) {
  FlightLog log;
  log.duration_s = 2;
  log.estimate.t_s = {0, 1};
  log.estimate.north_m = {0, 1};
  log.estimate.east_m = {0, 2};
  log.estimate.down_m = {0, -1};
  log.tracking_error_m = {{0, 1}, {0.25, 0.5}};
  log.tracking = TrackingSummary{2, 0.395, 0.5};
  const auto plots = plots_of(log);
  std::vector<std::string> ids;
  for (const auto& p : plots) ids.push_back(p.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"top-view", "altitude", "tracking-error"}));
  EXPECT_EQ(plots[2].note.rfind("RMS 0.40 m, max 0.50 m over 2 samples", 0), 0u) << plots[2].note;
  EXPECT_EQ(plots[1].series[0].y, (std::vector<double>{0, 1}));  // altitude is -down
}

TEST(Plots, APlotWithoutDataIsKeptInItsPlaceSayingWhatTheLogLacks) {
  FlightLog log;
  log.duration_s = 2;
  log.estimate_rates = {{0, 1}, {1, 2}, {0, 0}, {0, 0}};
  PlotOptions options;
  options.keep_lacking = true;
  const auto plots = plots_of(log, options);
  std::vector<std::string> ids;
  for (const auto& p : plots) ids.push_back(p.id);
  EXPECT_EQ(ids.front(), "top-view");
  for (const auto& p : plots) {
    EXPECT_FALSE(p.sources.empty()) << p.id;
    if (p.id == "rate-roll") {
      ASSERT_EQ(p.series.size(), 1u);
      EXPECT_EQ(p.series[0].title, "estimate");
      EXPECT_EQ(p.note.rfind("no rate setpoint: this log has no ATTITUDE_TARGET", 0), 0u) << p.note;
      EXPECT_TRUE(p.lacks.empty());
    }
    if (p.id == "sticks") {
      EXPECT_EQ(p.lacks, "this log has no MANUAL_CONTROL or RC_CHANNELS_OVERRIDE");
    }
    if (p.id == "motors") {
      EXPECT_EQ(p.lacks, "this log has no HIL_ACTUATOR_CONTROLS controls[0..3] from the vehicle");
    }
  }
  EXPECT_NE(std::find(ids.begin(), ids.end(), "sticks"), ids.end());
  EXPECT_EQ(plots_of(log).size(), 3u) << "without keep_lacking: the three rate plots only";
}

TEST(Plots, HtmlEscapesText) { EXPECT_EQ(html_escaped("<a href=\"x\">&</a>"), "&lt;a href=&quot;x&quot;&gt;&amp;&lt;/a&gt;"); }

}  // namespace
}  // namespace hitl::report
