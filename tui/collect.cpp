#include "tui/collect.h"

#include <algorithm>
#include <cmath>

#include "engine/telemetry/health.h"
#include "tui/draw.h"

namespace hitl::tui {

PathsPanel paths_from(const std::vector<hil::DataPathStats>& paths, bool paused, std::string caption) {
  PathsPanel panel;
  panel.caption = std::move(caption);
  for (const auto& p : paths) {
    PathRow row;
    row.name = p.name;
    row.message = p.message;
    row.outgoing = p.outgoing;
    row.expected_hz = p.expected_hz;
    row.rate_hz = p.stats.rate_hz;
    row.jitter_ms = p.stats.jitter_ms;
    row.max_gap_ms = p.stats.max_gap_ms;
    row.loss_pct = p.loss_pct;
    row.count = p.stats.count;
    const bool stale = p.stats.since_last_s < 0 || p.stats.since_last_s > telemetry::kStaleAfter_s;
    row.health = telemetry::rate_health(p.expected_hz, p.stats.rate_hz, stale);
    if (paused) row.note = "pause";
    else if (stale && p.stats.count > 0) row.note = "stale";
    panel.rows.push_back(std::move(row));
  }
  return panel;
}

DspHitlPanel dsp_hitl_from(const telemetry::DspHitlView& view, double pace) {
  DspHitlPanel panel;
  switch (view.state) {
    case telemetry::DspHitlView::State::Unavailable:
      panel.unavailable = view.reason;
      return panel;
    case telemetry::DspHitlView::State::Waiting: return panel;
    case telemetry::DspHitlView::State::Available: break;
  }
  static constexpr const char* kShort[] = {"sensor_imu", "IMU pub", "mag_baro", "MAG pub", "BARO pub"};
  panel.running = view.running;
  panel.age_s = view.age_s;
  for (std::size_t i = 0; i < view.counters.size(); ++i) {
    const auto& c = view.counters[i];
    CounterRow row;
    row.name = c.name;
    row.short_name = kShort[i];
    row.count = c.count;
    row.rate_hz = c.rate_hz;
    row.expected_hz = c.expected_hz * pace;
    row.stalled = c.stalled;
    row.health = c.rate_hz ? telemetry::rate_health(row.expected_hz, *c.rate_hz, c.stalled) : Health::Good;
    panel.counters.push_back(std::move(row));
  }
  return panel;
}

EkfPanel ekf_from(const vehicle::TelemetryFeedSnapshot& feed) {
  EkfPanel panel;
  if (!feed.connected) {
    panel.unavailable = feed.link.empty() ? "no autopilot link yet" : feed.link;
    return panel;
  }
  const auto& v = feed.vehicle;
  if (v.estimator) {
    const auto& e = *v.estimator;
    panel.flags = telemetry::estimator_flags(e.flags);
    panel.ratios = {{"vel", e.vel_ratio}, {"pos h", e.pos_horiz_ratio}, {"pos v", e.pos_vert_ratio}, {"mag", e.mag_ratio}};
    panel.horizontal_accuracy_m = e.pos_horiz_accuracy_m;
    panel.vertical_accuracy_m = e.pos_vert_accuracy_m;
  }
  const auto& err = feed.estimate_error;
  if (err.position_samples > 0) {
    panel.horizontal_error_m = err.horizontal_m;
    panel.vertical_error_m = err.vertical_m;
    panel.horizontal_rms_m = err.horizontal_rms_m;
  }
  if (err.attitude_samples > 0) {
    panel.attitude_error_deg = err.attitude_deg;
    panel.attitude_rms_deg = err.attitude_rms_deg;
  }
  if (!feed.truth_heard) panel.error_note = "no ground truth on this link (the session sends it to its clients)";
  else if (err.position_samples == 0 && err.attitude_samples == 0) panel.error_note = "waiting for LOCAL_POSITION_NED";
  return panel;
}

VehiclePanel vehicle_from(const vehicle::TelemetryFeedSnapshot& feed) {
  VehiclePanel panel;
  const auto& v = feed.vehicle;
  if (!feed.connected) panel.unavailable = feed.link.empty() ? "no autopilot link yet" : feed.link;
  else if (!v.heartbeat) panel.unavailable = "no HEARTBEAT from the autopilot yet";
  panel.armed = v.armed;
  panel.mode = v.mode;
  panel.landed = v.landed.value_or("");
  panel.in_air = v.in_air;
  panel.ready_to_arm = v.ready_to_arm;
  panel.battery_V = v.battery_V;
  panel.battery_A = v.battery_A;
  panel.battery_pct = v.battery_remaining_pct;
  if (v.p_NED_m) panel.altitude_m = -(*v.p_NED_m)[2];
  else if (v.relative_alt_m) panel.altitude_m = v.relative_alt_m;
  return panel;
}

std::vector<ActiveFault> active_faults_from(const std::vector<faults::FaultRecord>& records, double sim_time_s) {
  std::vector<ActiveFault> out;
  for (const auto& r : records) {
    if (r.end_s) continue;
    ActiveFault f{r.name, r.text(), r.start_s, std::nullopt};
    if (r.duration_s) f.left_s = std::max(0.0, r.start_s + *r.duration_s - sim_time_s);
    out.push_back(std::move(f));
  }
  return out;
}

std::string active_faults_text(const std::vector<ActiveFault>& active) {
  constexpr std::size_t kNamed = 3;  // the header has little room; the x menu lists them all
  if (active.empty()) return "";
  std::string out = "faults:";
  for (std::size_t i = 0; i < active.size() && i < kNamed; ++i)
    out += " " + active[i].text + (active[i].left_s ? format(" (%.0f s left)", std::ceil(*active[i].left_s)) : "");
  if (active.size() > kNamed) out += format(" +%zu more (x lists them)", active.size() - kNamed);
  return out;
}

}  // namespace hitl::tui
