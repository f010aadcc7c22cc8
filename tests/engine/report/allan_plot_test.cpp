// The report's Allan deviation plots (engine/report/allan_plot.h): the longest stretch at rest by
// the truth, a log-log curve per axis with the fitted white noise and floor marked, and the IMU's
// own figures marked when the simulator said them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/report/allan_plot.h"
#include "engine/telemetry/imu_noise_statement.h"

namespace hitl::report {
namespace {

constexpr double kRate_hz = 250.0;
constexpr double kGyroDensity = 4.887e-5;   // rad/s/sqrt(Hz)
constexpr double kAccelDensity = 6.865e-4;  // m/s^2/sqrt(Hz)

/// `rest_s` at rest, then `moving_s` turning at 10 deg/s, then `rest_after_s` at rest; the IMU's
/// white noise of the densities above, its truth at 50 Hz.
FlightLog log_of(double rest_s, double moving_s, double rest_after_s) {
  FlightLog log;
  log.simulated_time = true;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gyro(0.0, kGyroDensity * std::sqrt(kRate_hz) * 180.0 / M_PI);  // deg/s
  std::normal_distribution<double> accel(0.0, kAccelDensity * std::sqrt(kRate_hz));
  const double end_s = rest_s + moving_s + rest_after_s;
  for (std::size_t i = 0; i * (1.0 / kRate_hz) < end_s; ++i) {
    const double t = static_cast<double>(i) / kRate_hz;
    log.imu.t_s.push_back(t);
    for (int k = 0; k < 3; ++k) {
      log.imu.gyro_FRD_deg_s[k].push_back(gyro(rng));
      log.imu.accel_FRD_m_s2[k].push_back((k == 2 ? -9.80665 : 0.0) + accel(rng));
    }
    if (i % 5 == 0) {
      const bool moving = t >= rest_s && t < rest_s + moving_s;
      log.truth_velocity.t_s.push_back(t);
      log.truth_velocity.north_m_s.push_back(0.0);
      log.truth_velocity.east_m_s.push_back(0.0);
      log.truth_velocity.down_m_s.push_back(0.0);
      log.truth_rates.t_s.push_back(t);
      log.truth_rates.roll_deg_s.push_back(0.0);
      log.truth_rates.pitch_deg_s.push_back(0.0);
      log.truth_rates.yaw_deg_s.push_back(moving ? 10.0 : 0.0);
    }
  }
  log.duration_s = end_s;
  return log;
}

TEST(AllanPlot, TheLongestRestIsFoundByTheTruth) {
  const FlightLog log = log_of(40.0, 10.0, 70.0);
  const auto rest = longest_rest(log);
  ASSERT_TRUE(rest.has_value());
  EXPECT_NEAR(log.imu.t_s[rest->first], 50.0, 0.02);
  EXPECT_NEAR(log.imu.t_s[rest->last - 1], 120.0, 0.02);
  EXPECT_FALSE(longest_rest(log_of(20.0, 5.0, 20.0)).has_value()) << "none of 30 s";
  FlightLog no_truth = log;
  no_truth.truth_velocity = {};
  EXPECT_FALSE(longest_rest(no_truth).has_value());
}

TEST(AllanPlot, CurvesPerAxisOnLogAxesWithTheFitsMarked) {
  const FlightLog log = log_of(120.0, 0.0, 0.0);
  const auto plots = allan_plots(log);
  ASSERT_EQ(plots.size(), 2u);
  EXPECT_EQ(plots[0].id, "allan-gyro");
  EXPECT_EQ(plots[1].id, "allan-accel");
  for (const Plot& p : plots) {
    EXPECT_TRUE(p.log_axes);
    EXPECT_FALSE(p.time_axis);
    ASSERT_EQ(p.series.size(), 5u) << p.id << ": x, y, z and the fitted N and floor";
    EXPECT_EQ(p.series[0].title, "x");
    EXPECT_EQ(p.series[3].style, SeriesStyle::Estimate);
    EXPECT_EQ(p.series[3].title.rfind("fitted N/sqrt(tau), N = ", 0), 0u) << p.series[3].title;
    EXPECT_EQ(p.series[4].title.rfind("fitted 0.664 B, B = ", 0), 0u) << p.series[4].title;
    EXPECT_NE(p.note.find("the recording does not say the IMU's own figures"), std::string::npos) << p.note;
  }
  // The white noise read back: the gyro's curve at tau = 1 s is its density (within 10 %).
  const auto& x = plots[0].series[0];
  const double density_fit = plots[0].series[3].y.front() * std::sqrt(plots[0].series[3].x.front());
  EXPECT_NEAR(density_fit / kGyroDensity, 1.0, 0.1);
  for (std::size_t i = 0; i < x.x.size(); ++i) EXPECT_GT(x.y[i], 0.0);
}

TEST(AllanPlot, TheSimulatorsStatedFiguresAreMarked) {
  FlightLog log = log_of(60.0, 0.0, 0.0);
  log.events.push_back({0.0, Severity::Info, "vehicle 1", "imu noise (profile spoof): gyro N 1 rad/s/sqrt(Hz) B 0 rad/s, accel N 1 m/s^2/sqrt(Hz) B 0 m/s^2"});
  log.events.push_back({0.0, Severity::Info, "simulator",
                        telemetry::imu_noise_statement({"icm-42688-p", kGyroDensity, 0.0, kAccelDensity, 4e-4})});
  const auto plots = allan_plots(log);
  ASSERT_EQ(plots[0].series.size(), 6u) << "no floor for a B of 0";
  EXPECT_EQ(plots[0].series[5].title, "profile icm-42688-p: N/sqrt(tau), N = 4.89e-05");
  EXPECT_EQ(plots[0].series[5].style, SeriesStyle::Reference);
  ASSERT_EQ(plots[1].series.size(), 7u);
  EXPECT_EQ(plots[1].series[5].title, "profile icm-42688-p: N/sqrt(tau), N = 0.000687");
  EXPECT_EQ(plots[1].series[6].title, "profile icm-42688-p: 0.664 B, B = 0.0004");
  EXPECT_DOUBLE_EQ(plots[1].series[6].y.front(), 0.664 * 4e-4);
  EXPECT_NE(plots[0].note.find("(profile icm-42688-p): N 4.89e-05 rad/s/sqrt(Hz), B none (not modelled)"), std::string::npos)
      << plots[0].note;
}

TEST(AllanPlot, WithoutRestThePageHasNone) {
  FlightLog log = log_of(10.0, 50.0, 10.0);
  const auto plots = allan_plots(log);
  ASSERT_EQ(plots.size(), 2u);
  for (const Plot& p : plots) {
    EXPECT_TRUE(p.series.empty());
    EXPECT_EQ(p.sources.rfind("stretch of at least 30 s at rest", 0), 0u) << p.sources;
  }
  // Not a lack of the log: no plot in its place on the page.
  PlotOptions keep;
  keep.keep_lacking = true;
  for (const Plot& p : plots_of(log, keep)) EXPECT_NE(p.id.rfind("allan-", 0), 0u) << p.id;
  bool drawn = false;
  for (const Plot& p : plots_of(log_of(40.0, 0.0, 0.0), keep)) drawn = drawn || p.id == "allan-gyro";
  EXPECT_TRUE(drawn);
}

}  // namespace
}  // namespace hitl::report
