#include "engine/report/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>

#include "engine/report/allan_plot.h"
#include "engine/report/spectrum.h"

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

/// Samples per segment of the vibration spectrum: 2 s at 250 Hz, 0.49 Hz apart.
constexpr std::size_t kVibrationSegment = 512;
/// The caption names each axis' strongest frequency from here up (below: the flight's own motion).
constexpr double kVibrationAbove_Hz = 5.0;

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

TimeMarks time_marks(const FlightLog& log) {
  TimeMarks marks;
  marks.events = event_markers(log);
  const double end_s = log.start_s + log.duration_s;
  for (const auto& f : log.faults) marks.faults.push_back({f.start_s, f.end_s.value_or(end_s), f.label()});
  for (const auto& m : log.modes) marks.modes.push_back({m.start_s, m.end_s, m.mode});
  return marks;
}

std::vector<Plot> plots_of(const FlightLog& log, const PlotOptions& options) {
  const std::size_t n = options.max_points;
  const std::string time_label = log.simulated_time ? "simulated time (s)" : "time since the first record (s)";
  std::vector<Plot> plots;
  auto push = [&](Plot p) {
    if (p.series.empty()) {
      if (!options.keep_lacking) return;
      p.lacks = "this log has no " + p.sources;
      p.note.clear();
    }
    plots.push_back(std::move(p));
  };
  const std::string position_sources =
      "POSITION_TARGET_LOCAL_NED (setpoint), ODOMETRY with estimator MOCAP from the simulator (truth), LOCAL_POSITION_NED (estimate)";
  {
    Plot p{"top-view", "Top view: setpoint, truth and estimate", "east (m)", "north (m)", {}, false, true, ""};
    add_if(p, thinned("setpoint", SeriesStyle::Setpoint, log.setpoint.east_m, log.setpoint.north_m, n));
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth.east_m, log.truth.north_m, n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate.east_m, log.estimate.north_m, n));
    p.sources = position_sources;
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
    p.sources = position_sources;
    push(std::move(p));
  }
  if (log.px4) {
    const Px4Estimate& px4 = *log.px4;
    Plot a{"px4-altitude", "PX4's estimate (ULog) against truth: altitude", time_label, "altitude from home (m)", {}, true, false, ""};
    add_if(a, thinned("truth", SeriesStyle::Truth, log.truth.t_s, negated(log.truth.down_m), n));
    add_if(a, thinned("PX4 (ULog)", SeriesStyle::Estimate, px4.position.t_s, negated(px4.position.down_m), n));
    a.note = "PX4's vehicle_local_position from " + px4.path + " on the simulator's clock (in lockstep PX4's is the same)";
    if (px4.lag_s) a.note += "; PX4's heights follow the truth's " + figure("%.0f", *px4.lag_s * 1e3) + " ms later (fitted)";
    a.sources = "ODOMETRY with estimator MOCAP from the simulator (truth), PX4's ULog vehicle_local_position (PX4)";
    push(std::move(a));
    Plot o{"px4-offset", "PX4's estimate (ULog) minus truth", time_label, "estimate minus truth (m)", {}, true, false, ""};
    add_if(o, thinned("north", SeriesStyle::Plain, px4.minus_truth.t_s, px4.minus_truth.north_m, n));
    add_if(o, thinned("east", SeriesStyle::Plain, px4.minus_truth.t_s, px4.minus_truth.east_m, n));
    add_if(o, thinned("up", SeriesStyle::Plain, px4.minus_truth.t_s, negated(px4.minus_truth.down_m), n));
    const auto& m = px4.mean_offset_NED_m;
    o.note = "mean offset north " + figure("%.3f", m[0]) + " m, east " + figure("%.3f", m[1]) + " m, up " + figure("%.3f", -m[2]) +
             " m; RMS " + figure("%.3f", px4.rms_m) + " m over " + std::to_string(px4.minus_truth.size()) +
             " samples (the truth interpolated at each of PX4's times)";
    o.sources = a.sources;
    push(std::move(o));
  }
  {
    Plot p{"tracking-error", "Tracking error", time_label, "position error (m)", {}, true, false, ""};
    add_if(p, thinned("error against truth", SeriesStyle::Truth, log.tracking_error_m.t_s, log.tracking_error_m.value, n));
    if (log.tracking)
      p.note = "RMS " + figure("%.2f", log.tracking->rms_m) + " m, max " + figure("%.2f", log.tracking->max_m) + " m over " +
               std::to_string(log.tracking->samples) + " samples (the session's summary is of the same samples)";
    p.sources = "NAMED_VALUE_FLOAT trk_err from the trajectory pilot";
    push(std::move(p));
  }
  const std::array<std::tuple<const char*, std::vector<double> VelocityTrack::*, double>, 3> directions = {
      {{"north", &VelocityTrack::north_m_s, 1.0}, {"east", &VelocityTrack::east_m_s, 1.0}, {"up", &VelocityTrack::down_m_s, -1.0}}};
  for (const auto& [name, member, sign] : directions) {
    auto scaled = [&, m = member, k = sign](const VelocityTrack& v) {
      std::vector<double> out(v.*m);
      for (auto& x : out) x *= k;
      return out;
    };
    Plot p{std::string("velocity-") + name, std::string("Velocity: ") + name, time_label, std::string(name) + " (m/s)", {}, true, false, ""};
    add_if(p, thinned("setpoint", SeriesStyle::Setpoint, log.setpoint_velocity.t_s, scaled(log.setpoint_velocity), n));
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth_velocity.t_s, scaled(log.truth_velocity), n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate_velocity.t_s, scaled(log.estimate_velocity), n));
    p.sources = "POSITION_TARGET_LOCAL_NED vx, vy, vz (setpoint), ODOMETRY with estimator MOCAP from the simulator, its body "
                "velocity turned to NED (truth), LOCAL_POSITION_NED vx, vy, vz (estimate)";
    push(std::move(p));
  }
  const std::array<std::pair<const char*, std::vector<double> AttitudeTrack::*>, 3> axes = {
      {{"roll", &AttitudeTrack::roll_deg}, {"pitch", &AttitudeTrack::pitch_deg}, {"yaw", &AttitudeTrack::yaw_deg}}};
  for (const auto& [name, member] : axes) {
    Plot p{std::string("attitude-") + name, std::string("Attitude: ") + name, time_label, std::string(name) + " (deg)", {}, true, false, ""};
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth_attitude.t_s, log.truth_attitude.*member, n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate_attitude.t_s, log.estimate_attitude.*member, n));
    if (log.px4) add_if(p, thinned("PX4 (ULog)", SeriesStyle::Plain, log.px4->attitude.t_s, log.px4->attitude.*member, n));
    p.sources = std::string("ODOMETRY with estimator MOCAP from the simulator, its quaternion (truth), ATTITUDE (estimate)") +
                (log.px4 ? ", PX4's ULog vehicle_attitude (PX4)" : "");
    push(std::move(p));
  }
  const std::array<std::pair<const char*, std::vector<double> RateTrack::*>, 3> rate_axes = {
      {{"roll", &RateTrack::roll_deg_s}, {"pitch", &RateTrack::pitch_deg_s}, {"yaw", &RateTrack::yaw_deg_s}}};
  for (const auto& [name, member] : rate_axes) {
    Plot p{std::string("rate-") + name, std::string("Rate tracking: ") + name, time_label, std::string(name) + " rate (deg/s)", {}, true, false, ""};
    add_if(p, thinned("setpoint", SeriesStyle::Setpoint, log.rate_setpoint.t_s, log.rate_setpoint.*member, n));
    add_if(p, thinned("truth", SeriesStyle::Truth, log.truth_rates.t_s, log.truth_rates.*member, n));
    add_if(p, thinned("estimate", SeriesStyle::Estimate, log.estimate_rates.t_s, log.estimate_rates.*member, n));
    const bool px4_rates = log.px4 && (log.px4->rate_setpoint.size() > 0 || log.px4->rates.size() > 0);
    if (log.px4) {
      add_if(p, thinned("PX4 setpoint (ULog)", SeriesStyle::Setpoint, log.px4->rate_setpoint.t_s, log.px4->rate_setpoint.*member, n));
      add_if(p, thinned("PX4 (ULog)", SeriesStyle::Plain, log.px4->rates.t_s, log.px4->rates.*member, n));
    }
    p.sources = std::string("ATTITUDE_TARGET body rates (setpoint), ODOMETRY with estimator MOCAP from the simulator, rollspeed, "
                            "pitchspeed, yawspeed (truth), ATTITUDE rollspeed, pitchspeed, yawspeed (estimate)") +
                (px4_rates ? ", PX4's ULog vehicle_rates_setpoint (PX4 setpoint) and vehicle_angular_velocity (PX4)" : "");
    if (log.rate_setpoint.size() == 0 && !(log.px4 && log.px4->rate_setpoint.size() > 0) &&
        (log.truth_rates.size() > 0 || log.estimate_rates.size() > 0))
      p.note = std::string("no rate setpoint: this log has no ATTITUDE_TARGET with body rates (the vehicle did not stream it on "
                           "this link)") + (log.px4 ? " and PX4's ULog no vehicle_rates_setpoint" : "");
    push(std::move(p));
  }
  {
    Plot p{"motors", "Motor commands (HIL_ACTUATOR_CONTROLS)", time_label, "command (0..1)", {}, true, false, ""};
    for (std::size_t k = 0; k < log.motors.size(); ++k)
      add_if(p, thinned("motor " + std::to_string(k), SeriesStyle::Plain, log.motors[k].t_s, log.motors[k].value, n));
    p.sources = "HIL_ACTUATOR_CONTROLS controls[0..3] from the vehicle";
    push(std::move(p));
  }
  {
    const bool manual = log.manual_control.size() > 0;
    const Sticks& sticks = manual ? log.manual_control : log.rc_override;
    Plot p{"sticks", "Sticks", time_label, "stick (full scale 1)", {}, true, false, ""};
    for (const auto& [name, series] : {std::pair{"roll", &sticks.roll}, std::pair{"pitch", &sticks.pitch},
                                       std::pair{"throttle", &sticks.throttle}, std::pair{"yaw", &sticks.yaw}})
      add_if(p, thinned(name, SeriesStyle::Plain, series->t_s, series->value, n));
    p.sources = manual || log.rc_override.size() == 0
                    ? "MANUAL_CONTROL y (roll), x (pitch), z (throttle), r (yaw), each / 1000"
                    : "RC_CHANNELS_OVERRIDE channels 1 to 4 (roll, pitch, throttle, yaw), each (us - 1500) / 500";
    if (p.series.empty()) p.sources = "MANUAL_CONTROL or RC_CHANNELS_OVERRIDE";
    else if (manual && log.rc_override.size() > 0) p.note = "the log has RC_CHANNELS_OVERRIDE too: MANUAL_CONTROL is drawn";
    push(std::move(p));
  }
  const std::array<const char*, 3> imu_axes = {"x (forward)", "y (right)", "z (down)"};
  {
    Plot a{"imu-accel", "Raw IMU: accelerometer", time_label, "specific force, body FRD (m/s^2)", {}, true, false, ""};
    Plot g{"imu-gyro", "Raw IMU: gyro", time_label, "body rate, FRD (deg/s)", {}, true, false, ""};
    for (std::size_t k = 0; k < 3; ++k) {
      add_if(a, thinned(imu_axes[k], SeriesStyle::Plain, log.imu.t_s, log.imu.accel_FRD_m_s2[k], n));
      add_if(g, thinned(imu_axes[k], SeriesStyle::Plain, log.imu.t_s, log.imu.gyro_FRD_deg_s[k], n));
    }
    a.sources = "HIL_SENSOR xacc, yacc, zacc from the simulator (the IMU as the flight stack received it)";
    g.sources = "HIL_SENSOR xgyro, ygyro, zgyro from the simulator (the IMU as the flight stack received it)";
    push(std::move(a));
    push(std::move(g));
  }
  {
    const double rate_hz = sample_rate_hz(log.imu.t_s);
    Plot p{"vibration", "Vibration: accelerometer spectrum", "frequency (Hz)", "amplitude (m/s^2)", {}, false, false, ""};
    std::size_t segments = 0;
    std::string peaks;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto spectrum = amplitude_spectrum(log.imu.accel_FRD_m_s2[k], rate_hz, kVibrationSegment);
      segments = spectrum.segments;
      std::optional<std::size_t> best;  // the strongest above the flight's own motion
      for (std::size_t i = 0; i < spectrum.freq_hz.size(); ++i)
        if (spectrum.freq_hz[i] >= kVibrationAbove_Hz && (!best || spectrum.amplitude[i] > spectrum.amplitude[*best])) best = i;
      if (best)
        peaks += std::string(peaks.empty() ? "" : ", ") + imu_axes[k] + " " + figure("%.1f", spectrum.freq_hz[*best]) + " Hz (" +
                 figure("%.2f", spectrum.amplitude[*best]) + " m/s^2)";
      add_if(p, thinned(imu_axes[k], SeriesStyle::Plain, spectrum.freq_hz, spectrum.amplitude, n));
    }
    p.sources = "HIL_SENSOR xacc, yacc, zacc from the simulator";
    if (!p.series.empty())
      p.note = "Welch's method over the whole log: " + std::to_string(segments) + " segments of " + std::to_string(kVibrationSegment) +
               " samples at the IMU's " + figure("%.0f", rate_hz) + " Hz (" + figure("%.2f", rate_hz / kVibrationSegment) +
               " Hz apart), each half over the one before, its mean removed, Hann window; the amplitude of a sinusoid at each "
               "frequency, RMS over the segments (a vibration of a few seconds shows diluted by the rest). Above half the IMU's "
               "rate (" + figure("%.0f", rate_hz / 2) + " Hz) a vibration folds back below it. Strongest from " +
               figure("%.0f", kVibrationAbove_Hz) + " Hz: " + peaks;
    push(std::move(p));
  }
  {
    Plot p{"gps", "GPS quality", time_label, "fix type, satellites, eph and epv / 100", {}, true, false, ""};
    for (const auto& [who, q] : {std::pair{"HIL_GPS", &log.sent_gps}, std::pair{"GPS_RAW_INT", &log.vehicle_gps}}) {
      const std::string tail = std::string(" (") + who + ")";
      add_if(p, thinned("fix type" + tail, SeriesStyle::Plain, q->fix_type.t_s, q->fix_type.value, n));
      add_if(p, thinned("satellites" + tail, SeriesStyle::Plain, q->satellites.t_s, q->satellites.value, n));
      add_if(p, thinned("eph" + tail, SeriesStyle::Plain, q->eph.t_s, q->eph.value, n));
      add_if(p, thinned("epv" + tail, SeriesStyle::Plain, q->epv.t_s, q->epv.value, n));
    }
    p.sources = "HIL_GPS from the simulator (what the flight stack was given), GPS_RAW_INT from the vehicle";
    if (!p.series.empty())
      p.note = "fix type 0-1 none, 2 2D, 3 3D; eph and epv over 100: HDOP and VDOP by MAVLink's words, metres as PX4 reads "
               "HIL_GPS; a gps-loss fault is a gap in the HIL_GPS series (drawn across on the interactive page: see its band)";
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
    p.sources = j.sources = "the arrivals of HIL_SENSOR, HIL_GPS and ODOMETRY (VIO) from the simulator and HIL_ACTUATOR_CONTROLS "
                            "from the vehicle, by their tlog timestamps";
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
    p.sources = "NAMED_VALUE_INT sim_lat50, sim_lat99, sim_latmx from the simulator";
    if (p.series.empty()) p.note.clear();
    push(std::move(p));
  }
  {
    Plot p{"ekf", "EKF test ratios (ESTIMATOR_STATUS)", time_label, "test ratio (1: rejected)", {}, true, false, ""};
    for (std::size_t k = 0; k < log.ekf_ratios.size(); ++k)
      add_if(p, thinned(kEkfRatioNames[k], SeriesStyle::Plain, log.ekf_ratios[k].t_s, log.ekf_ratios[k].value, n));
    p.sources = "ESTIMATOR_STATUS from the vehicle";
    push(std::move(p));
  }
  if (log.px4) {
    // PX4's EKF2 from its ULog: its innovations (measurement minus prediction) by kind, and its test ratios.
    const Px4Estimate& px4 = *log.px4;
    const std::array<std::tuple<const char*, const char*, const char*>, 5> groups = {{{"velocity", "velocity", "innovation (m/s)"},
                                                                                      {"position", "horizontal position", "innovation (m)"},
                                                                                      {"height", "height", "innovation (m)"},
                                                                                      {"magnetometer", "magnetometer", "innovation (gauss)"},
                                                                                      {"heading", "heading", "innovation (deg)"}}};
    const std::string zero = px4.innovations_zero.empty() ? "" : "0 throughout, not drawn (not fused): " + [&] {
      std::string z;
      for (const auto& name : px4.innovations_zero) z += (z.empty() ? "" : ", ") + name;
      return z;
    }();
    bool any = false;
    for (const auto& [group, words, y_label] : groups) {
      Plot p{std::string("px4-innovations-") + group, std::string("PX4's EKF innovations (ULog): ") + words, time_label, y_label, {}, true, false, ""};
      for (const auto& i : px4.innovations)
        if (i.group == group) add_if(p, thinned(i.name, SeriesStyle::Plain, i.value.t_s, i.value.value, n));
      p.sources = "PX4's ULog estimator_innovations";
      if (p.series.empty()) continue;  // a kind EKF2 did not fuse: named under the first plot
      if (!any && !zero.empty()) p.note = zero;
      any = true;
      push(std::move(p));
    }
    Plot r{"px4-test-ratios", "PX4's EKF innovation test ratios (ULog)", time_label, "test ratio (1: rejected)", {}, true, false, ""};
    for (const auto& i : px4.test_ratios) add_if(r, thinned(i.name, SeriesStyle::Plain, i.value.t_s, i.value.value, n));
    r.sources = "PX4's ULog estimator_innovation_test_ratios";
    if (!any) {
      Plot p{"px4-innovations", "PX4's EKF innovations (ULog)", time_label, "innovation", {}, true, false, ""};
      p.sources = "PX4's ULog estimator_innovations" +
                  (px4.innovations_missing.empty() ? std::string(" other than 0") : " (" + px4.innovations_missing + ")");
      push(std::move(p));
    }
    push(std::move(r));
  }
  for (std::size_t k = 0; k < log.field_plots.size(); ++k) {
    const FieldPlot& f = log.field_plots[k];
    Plot p{"field-" + std::to_string(k + 1), f.text, time_label, "value", {}, true, false, ""};
    std::string messages, units, left_out, absent;
    bool one_unit = true;
    for (const auto& s : f.series) {
      add_if(p, thinned(s.title, SeriesStyle::Plain, s.values.t_s, s.values.value, n));
      if (messages.find(s.message) == std::string::npos) messages += (messages.empty() ? "" : ", ") + s.message;
      if (&s == &f.series.front()) units = s.units;
      one_unit = one_unit && !s.units.empty() && s.units == units;
      if (s.not_finite > 0)
        left_out += (left_out.empty() ? "" : ", ") + std::to_string(s.not_finite) + " of " + s.title;
      if (s.values.size() == 0 && s.not_finite == 0) absent += (absent.empty() ? "" : ", ") + s.title;
    }
    if (one_unit) p.y_label = units;
    p.sources = messages + " (every sender; hitl report --plot)";
    if (!left_out.empty()) p.note = "values that are not finite left out: " + left_out;
    if (!absent.empty() && !p.series.empty())
      p.note += std::string(p.note.empty() ? "" : "; ") + "not drawn, its message not in this log: " + absent;
    if (p.series.empty()) {
      if (!options.keep_lacking) continue;
      p.sources = messages;  // "this log has no ATTITUDE"
    }
    push(std::move(p));
  }
  for (auto& p : plots) {
    if (p.time_axis) {
      p.x_min = log.start_s;
      p.x_max = log.start_s + log.duration_s;
    }
    drop_indistinct(p, options.indistinct_fraction);
  }
  // allan_plot.h: log-log, ~40 points a curve, none dropped; a flight without 30 s at rest lacks
  // nothing a report needs, so no plot in its place.
  for (auto& p : allan_plots(log))
    if (!p.series.empty()) push(std::move(p));
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
