#include "engine/report/allan_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>

#include "engine/report/spectrum.h"
#include "engine/telemetry/allan_deviation.h"
#include "engine/telemetry/imu_noise_statement.h"

namespace hitl::report {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

std::string figure(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

/// The IMU's figures as the simulator said them (its first statement), if it did.
std::optional<telemetry::ImuNoiseFigures> stated_figures(const FlightLog& log) {
  for (const auto& e : log.events)
    if (e.source == "simulator")
      if (auto f = telemetry::parse_imu_noise_statement(e.text)) return f;
  return std::nullopt;
}

/// A line across the curve's taus: the white noise N/sqrt(tau), or a floor; `style` Estimate for
/// what was fitted to the recording, Reference for the IMU's own figures.
PlotSeries white_line(const std::string& title, double n, double tau0, double tau1, SeriesStyle style) {
  PlotSeries s;
  s.title = title;
  s.style = style;
  for (double tau : {tau0, tau1}) s.x.push_back(tau), s.y.push_back(n / std::sqrt(tau));
  s.samples = 2;
  return s;
}

PlotSeries floor_line(const std::string& title, double b, double tau0, double tau1, SeriesStyle style) {
  PlotSeries s;
  s.title = title;
  s.style = style;
  s.x = {tau0, tau1};
  s.y = {0.664 * b, 0.664 * b};
  s.samples = 2;
  return s;
}

}  // namespace

std::optional<RestStretch> longest_rest(const FlightLog& log) {
  const auto& v = log.truth_velocity;
  const auto& w = log.truth_rates;
  if (v.size() == 0 || w.size() == 0 || log.imu.size() == 0) return std::nullopt;
  auto still_at = [&](std::size_t vi, std::size_t wi) {
    const double speed = std::sqrt(v.north_m_s[vi] * v.north_m_s[vi] + v.east_m_s[vi] * v.east_m_s[vi] + v.down_m_s[vi] * v.down_m_s[vi]);
    const double rate = std::sqrt(w.roll_deg_s[wi] * w.roll_deg_s[wi] + w.pitch_deg_s[wi] * w.pitch_deg_s[wi] +
                                  w.yaw_deg_s[wi] * w.yaw_deg_s[wi]);
    return speed < kRestSpeed_m_s && rate < kRestRate_deg_s;  // NaN (a damaged record) is not at rest
  };
  RestStretch best, current;
  bool in_rest = false;
  std::size_t vi = 0, wi = 0;
  const auto& t = log.imu.t_s;
  for (std::size_t i = 0; i < t.size(); ++i) {
    // The truth's latest sample at or before this IMU sample (none yet: not known to be at rest).
    while (vi + 1 < v.size() && v.t_s[vi + 1] <= t[i]) ++vi;
    while (wi + 1 < w.size() && w.t_s[wi + 1] <= t[i]) ++wi;
    const bool rest = v.t_s[vi] <= t[i] && w.t_s[wi] <= t[i] && still_at(vi, wi);
    if (rest && !in_rest) current = {i, i};
    if (rest) current.last = i + 1;
    if (!rest && in_rest && current.size() > best.size()) best = current;
    in_rest = rest;
  }
  if (in_rest && current.size() > best.size()) best = current;
  if (best.size() < 2 || t[best.last - 1] - t[best.first] < kMinRest_s) return std::nullopt;
  return best;
}

std::vector<Plot> allan_plots(const FlightLog& log) {
  Plot gyro{"allan-gyro", "Allan deviation at rest: gyro", "averaging time tau (s)", "Allan deviation (rad/s)", {}, false, false, ""};
  Plot accel{"allan-accel", "Allan deviation at rest: accelerometer", "averaging time tau (s)", "Allan deviation (m/s^2)", {}, false, false, ""};
  gyro.log_axes = accel.log_axes = true;
  gyro.sources = accel.sources =
      "stretch of at least " + figure(kMinRest_s) + " s at rest (the simulator's truth ODOMETRY still) with HIL_SENSOR from the simulator";
  const auto rest = longest_rest(log);
  if (!rest) return {gyro, accel};
  const std::size_t first = rest->first, n = std::min(rest->size(), kMaxAllanSamples);
  const std::vector<double> t(log.imu.t_s.begin() + static_cast<std::ptrdiff_t>(first),
                              log.imu.t_s.begin() + static_cast<std::ptrdiff_t>(first + n));
  const double rate_hz = sample_rate_hz(t);
  const auto stated = stated_figures(log);
  const std::array<const char*, 3> axes = {"x", "y", "z"};
  for (Plot* plot : {&gyro, &accel}) {
    const bool is_gyro = plot == &gyro;
    const char* unit = is_gyro ? "rad/s" : "m/s^2";
    double n_sum = 0, b_sum = 0, tau0 = 0, tau1 = 0;
    std::string fits;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto& source = is_gyro ? log.imu.gyro_FRD_deg_s[k] : log.imu.accel_FRD_m_s2[k];
      std::vector<double> x(source.begin() + static_cast<std::ptrdiff_t>(first), source.begin() + static_cast<std::ptrdiff_t>(first + n));
      if (is_gyro)
        for (double& v : x) v *= kDegToRad;
      const auto curve = telemetry::overlapping_allan_deviation(std::span<const double>(x), rate_hz);
      if (curve.empty()) continue;
      const auto fit = telemetry::fit_allan(curve);
      PlotSeries s;
      s.title = axes[k];
      for (const auto& p : curve) s.x.push_back(p.tau_s), s.y.push_back(p.deviation);
      s.samples = s.x.size();
      tau0 = s.x.front(), tau1 = s.x.back();
      plot->series.push_back(std::move(s));
      n_sum += fit.noise_density, b_sum += fit.bias_instability;
      fits += std::string(fits.empty() ? "" : "; ") + axes[k] + " N " + figure(fit.noise_density) + ", B " + figure(fit.bias_instability);
    }
    if (plot->series.empty()) continue;
    const double axes_n = static_cast<double>(plot->series.size());
    const double n_fit = n_sum / axes_n, b_fit = b_sum / axes_n;
    plot->series.push_back(white_line("fitted N/sqrt(tau), N = " + figure(n_fit), n_fit, tau0, tau1, SeriesStyle::Estimate));
    plot->series.push_back(floor_line("fitted 0.664 B, B = " + figure(b_fit), b_fit, tau0, tau1, SeriesStyle::Estimate));
    std::string marks;
    if (stated) {
      const double n_stated = is_gyro ? stated->gyro_noise_density : stated->accel_noise_density;
      const double b_stated = is_gyro ? stated->gyro_bias_instability : stated->accel_bias_instability;
      const std::string whose = stated->profile.empty() ? "the IMU's" : "profile " + stated->profile + ":";
      if (n_stated > 0) plot->series.push_back(white_line(whose + " N/sqrt(tau), N = " + figure(n_stated), n_stated, tau0, tau1, SeriesStyle::Reference));
      if (b_stated > 0) plot->series.push_back(floor_line(whose + " 0.664 B, B = " + figure(b_stated), b_stated, tau0, tau1, SeriesStyle::Reference));
      marks = "marked: the mean of the axes' fits and the figures the simulator said its IMU has" +
              (stated->profile.empty() ? std::string() : " (profile " + stated->profile + ")") + ": N " + figure(n_stated) + " " + unit +
              "/sqrt(Hz), B " + (b_stated > 0 ? figure(b_stated) + " " + unit : std::string("none (not modelled)"));
    } else {
      marks = "marked: the mean of the axes' fits; the recording does not say the IMU's own figures (a recording of hitl sim "
              "says them in its first STATUSTEXT)";
    }
    plot->note = "overlapping Allan deviation over " + figure(t.back() - t.front()) + " s at rest from " + figure(t.front()) + " s (" +
                 std::to_string(n) + " samples at " + figure(rate_hz) + " Hz); N: the tau = 1 s value of the -1/2 slope (" + unit +
                 "/sqrt(Hz)), B: the minimum / 0.664 (" + unit + "): " + fits + "; " + marks;
  }
  return {gyro, accel};
}

}  // namespace hitl::report
