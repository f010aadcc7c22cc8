#include "engine/report/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hitl::report {

PlotSeries thinned(std::string title, SeriesStyle style, const std::vector<double>& x, const std::vector<double>& y,
                   std::size_t max_points) {
  PlotSeries s;
  s.title = std::move(title);
  s.style = style;
  s.samples = x.size();
  if (x.empty()) return s;
  const std::size_t stride = max_points == 0 ? 1 : (x.size() + max_points - 1) / max_points;
  auto keep = [&](std::size_t i) {
    if (!s.x.empty() && s.x.back() == x[i] && s.y.back() == y[i]) return;  // gnuplot draws a repeat once, so do we
    s.x.push_back(x[i]);
    s.y.push_back(y[i]);
  };
  for (std::size_t i = 0; i < x.size(); i += stride) keep(i);
  if ((x.size() - 1) % stride != 0) keep(x.size() - 1);
  return s;
}

namespace {

std::vector<double> negated(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = -v[i];
  return out;
}

void add_if(Plot& plot, PlotSeries series) {
  if (!series.x.empty()) plot.series.push_back(std::move(series));
}

std::string figure(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

/// Drops each point within `fraction` of the plot's extent (both axes) of the last one kept: what a
/// drawing cannot tell apart (gnuplot's SVG draws a repeated device point once), so that the points a
/// figure claims are the points its SVG draws.
void drop_indistinct(Plot& plot, double fraction) {
  double x0 = plot.x_min, x1 = plot.x_max, y0 = 0, y1 = 0;
  bool first = plot.x_max <= plot.x_min;
  bool first_y = true;
  for (const auto& s : plot.series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (first) x0 = x1 = s.x[i], first = false;
      if (first_y) y0 = y1 = s.y[i], first_y = false;
      x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]), y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
    }
  const double tol_x = fraction * (x1 - x0), tol_y = fraction * (y1 - y0);
  for (auto& s : plot.series) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (kept > 0 && std::abs(s.x[i] - s.x[kept - 1]) <= tol_x && std::abs(s.y[i] - s.y[kept - 1]) <= tol_y) continue;
      s.x[kept] = s.x[i];
      s.y[kept] = s.y[i];
      ++kept;
    }
    s.x.resize(kept);
    s.y.resize(kept);
  }
}

}  // namespace

std::vector<EventMarker> event_markers(const FlightLog& log, std::size_t max_markers) {
  std::vector<EventMarker> out;
  for (const auto& e : log.events) {
    if (out.size() >= max_markers) break;
    out.push_back({e.t_s, e.severity});
  }
  return out;
}

std::vector<Plot> plots_of(const FlightLog& log, const PlotOptions& options) {
  const std::size_t n = options.max_points;
  const std::string time_label = log.simulated_time ? "simulated time (s)" : "time since the first record (s)";
  std::vector<Plot> plots;
  auto push = [&](Plot p) {
    if (!p.series.empty()) plots.push_back(std::move(p));
  };
  {
    Plot p{"top-view", "Top view: setpoint, truth and estimate", "east (m)", "north (m)", {}, false, true, ""};
    add_if(p, thinned("setpoint", SeriesStyle::Setpoint, log.setpoint.east_m, log.setpoint.north_m, n));
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth.east_m, log.truth.north_m, n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate.east_m, log.estimate.north_m, n));
    push(std::move(p));
  }
  {
    Plot p{"altitude", "Altitude", time_label, "altitude from home (m)", {}, true, false, ""};
    add_if(p, thinned("setpoint", SeriesStyle::Setpoint, log.setpoint.t_s, negated(log.setpoint.down_m), n));
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth.t_s, negated(log.truth.down_m), n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate.t_s, negated(log.estimate.down_m), n));
    if (log.truth_rest_down_m)
      p.note = "every height from home, the origin of PX4's local position: 0.00 m on the ground (the truth's body origin "
               "rests " + figure("%.2f", -*log.truth_rest_down_m) + " m above it)";
    push(std::move(p));
  }
  if (log.px4) {
    const Px4Estimate& px4 = *log.px4;
    Plot a{"px4-altitude", "PX4's estimate (ULog) against truth: altitude", time_label, "altitude from home (m)", {}, true, false, ""};
    add_if(a, thinned("truth", SeriesStyle::Truth, log.truth.t_s, negated(log.truth.down_m), n));
    add_if(a, thinned("PX4 (ULog)", SeriesStyle::Estimate, px4.position.t_s, negated(px4.position.down_m), n));
    a.note = "PX4's vehicle_local_position from " + px4.path + " on the simulator's clock (in lockstep PX4's is the same)";
    if (px4.lag_s) a.note += "; PX4's heights follow the truth's " + figure("%.0f", *px4.lag_s * 1e3) + " ms later (fitted)";
    push(std::move(a));
    Plot o{"px4-offset", "PX4's estimate (ULog) minus truth", time_label, "estimate minus truth (m)", {}, true, false, ""};
    add_if(o, thinned("north", SeriesStyle::Plain, px4.minus_truth.t_s, px4.minus_truth.north_m, n));
    add_if(o, thinned("east", SeriesStyle::Plain, px4.minus_truth.t_s, px4.minus_truth.east_m, n));
    add_if(o, thinned("up", SeriesStyle::Plain, px4.minus_truth.t_s, negated(px4.minus_truth.down_m), n));
    const auto& m = px4.mean_offset_NED_m;
    o.note = "mean offset north " + figure("%.3f", m[0]) + " m, east " + figure("%.3f", m[1]) + " m, up " + figure("%.3f", -m[2]) +
             " m; RMS " + figure("%.3f", px4.rms_m) + " m over " + std::to_string(px4.minus_truth.size()) +
             " samples (the truth interpolated at each of PX4's times)";
    push(std::move(o));
  }
  if (log.tracking) {
    Plot p{"tracking-error", "Tracking error", time_label, "position error (m)", {}, true, false, ""};
    add_if(p, thinned("error against truth", SeriesStyle::Truth, log.tracking_error_m.t_s, log.tracking_error_m.value, n));
    p.note = "RMS " + figure("%.2f", log.tracking->rms_m) + " m, max " + figure("%.2f", log.tracking->max_m) + " m over " +
             std::to_string(log.tracking->samples) + " samples (the session's summary is of the same samples)";
    push(std::move(p));
  }
  const std::array<std::pair<const char*, std::vector<double> AttitudeTrack::*>, 3> axes = {
      {{"roll", &AttitudeTrack::roll_deg}, {"pitch", &AttitudeTrack::pitch_deg}, {"yaw", &AttitudeTrack::yaw_deg}}};
  for (const auto& [name, member] : axes) {
    Plot p{std::string("attitude-") + name, std::string("Attitude: ") + name, time_label, std::string(name) + " (deg)", {}, true, false, ""};
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth_attitude.t_s, log.truth_attitude.*member, n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate_attitude.t_s, log.estimate_attitude.*member, n));
    if (log.px4) add_if(p, thinned("PX4 (ULog)", SeriesStyle::Plain, log.px4->attitude.t_s, log.px4->attitude.*member, n));
    push(std::move(p));
  }
  {
    Plot p{"motors", "Motor commands (HIL_ACTUATOR_CONTROLS)", time_label, "command (0..1)", {}, true, false, ""};
    for (std::size_t k = 0; k < log.motors.size(); ++k)
      add_if(p, thinned("motor " + std::to_string(k + 1), SeriesStyle::Plain, log.motors[k].t_s, log.motors[k].value, n));
    push(std::move(p));
  }
  {
    Plot p{"rates", "Data path rates against expected", time_label, "messages per second of the log's time", {}, true, false, ""};
    Plot j{"jitter", "Data path jitter", time_label, "wall-clock inter-arrival std (ms)", {}, true, false, ""};
    for (const auto& path : log.paths) {
      add_if(p, thinned(path.name, SeriesStyle::Plain, path.rate_hz.t_s, path.rate_hz.value, n));
      if (path.expected_hz && !path.rate_hz.t_s.empty())
        add_if(p, thinned(path.name + " expected", SeriesStyle::Reference, {path.rate_hz.t_s.front(), path.rate_hz.t_s.back()},
                          {*path.expected_hz, *path.expected_hz}, n));
      add_if(j, thinned(path.name, SeriesStyle::Plain, path.jitter_ms.t_s, path.jitter_ms.value, n));
    }
    p.note = "1 s windows; expected: HIL_SENSOR 250 Hz, ODOMETRY the VIO rate, HIL_ACTUATOR_CONTROLS one per HIL_SENSOR "
             "in lockstep, else the board's 200 Hz stream";
    push(std::move(p));
    push(std::move(j));
  }
  {
    Plot p{"loop-latency", "Loop latency (HIL_SENSOR sent to its HIL_ACTUATOR_CONTROLS received)", time_label,
           "wall-clock latency (ms)", {}, true, false, ""};
    auto ms = [](const Series& s) {
      std::vector<double> v(s.value);
      for (auto& x : v) x *= 1e-3;
      return v;
    };
    const auto& l = log.loop_latency;
    add_if(p, thinned("p50", SeriesStyle::Plain, l.p50_us.t_s, ms(l.p50_us), n));
    add_if(p, thinned("p99", SeriesStyle::Plain, l.p99_us.t_s, ms(l.p99_us), n));
    add_if(p, thinned("max", SeriesStyle::Plain, l.max_us.t_s, ms(l.max_us), n));
    p.note = "over the session so far, as its status said each second of wall and of simulated time (NAMED_VALUE_INT "
             "sim_lat50, sim_lat99, sim_latmx)";
    push(std::move(p));
  }
  {
    Plot p{"ekf", "EKF test ratios (ESTIMATOR_STATUS)", time_label, "test ratio (1: rejected)", {}, true, false, ""};
    for (std::size_t k = 0; k < log.ekf_ratios.size(); ++k)
      add_if(p, thinned(kEkfRatioNames[k], SeriesStyle::Plain, log.ekf_ratios[k].t_s, log.ekf_ratios[k].value, n));
    push(std::move(p));
  }
  for (auto& p : plots) {
    if (p.time_axis) {
      p.x_min = log.start_s;
      p.x_max = log.start_s + log.duration_s;
    }
    drop_indistinct(p, options.indistinct_fraction);
  }
  for (auto& p : plots)
    for (const auto& s : p.series)
      if (s.x.size() < s.samples && s.style != SeriesStyle::Reference) {
        p.note += std::string(p.note.empty() ? "" : "; ") + "series with more than " + std::to_string(n) +
                  " samples are drawn thinned evenly to about that many points (data-series on the figure: points "
                  "drawn, samples recorded)";
        break;
      }
  return plots;
}

}  // namespace hitl::report
