#include "engine/campaign/flight_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/hil/snapshot_json.h"

namespace hitl::campaign {

namespace {

nlohmann::json per_sim_second(const hil::SessionSnapshot& s, const std::map<std::string, hil::StreamCount>& counts,
                              const char* name) {
  if (!(s.sim_time_s > 0)) return nullptr;
  const auto it = counts.find(name);
  return it == counts.end() ? 0.0 : static_cast<double>(it->second.count) / s.sim_time_s;
}

}  // namespace

nlohmann::json flight_summary_json(const Campaign& campaign, const Flight& flight, const hil::SessionSnapshot& s,
                                   const std::string& end, const StackFigures& stack, const report::FlightLog* log) {
  auto j = hil::snapshot_json(s, true);
  j["end"] = end;
  j["rates_hz"] = {{"HIL_SENSOR", per_sim_second(s, s.sent, "HIL_SENSOR")},
                   {"HIL_GPS", per_sim_second(s, s.sent, "HIL_GPS")},
                   {"ODOMETRY", per_sim_second(s, s.sent, "ODOMETRY")},
                   {"HIL_ACTUATOR_CONTROLS", per_sim_second(s, s.received, "HIL_ACTUATOR_CONTROLS")}};
  j["stack"] = {{"kind", to_string(campaign.stack)},
                {"version", stack_version(campaign)},
                {"armed", stack.armed},
                {"mode", stack.mode},
                {"landed_state", stack.landed_state},
                {"hil_sensor_received", stack.hil_sensor_received},
                {"hil_gps_received", stack.hil_gps_received},
                {"odometry_received", stack.odometry_received},
                {"actuators_sent", stack.actuators_sent},
                {"malformed", stack.malformed}};
  nlohmann::json ratios = nlohmann::json::object();
  for (std::size_t i = 0; i < report::kEkfRatioNames.size(); ++i) {
    std::string name = report::kEkfRatioNames[i];
    std::replace(name.begin(), name.end(), ' ', '_');
    nlohmann::json largest = nullptr;
    if (log != nullptr)
      for (const double v : log->ekf_ratios[i].value)
        if (std::isfinite(v) && (largest.is_null() || v > largest.get<double>())) largest = v;
    ratios[name] = largest;
  }
  j["ekf_test_ratios"] = ratios;
  nlohmann::json events = nlohmann::json::array();
  if (log != nullptr)
    for (const auto& e : log->events) {
      if (events.size() >= kMaxSummaryEvents) break;
      events.push_back({{"t_s", e.t_s}, {"source", e.source}, {"text", e.text}});
    }
  j["events"] = events;
  nlohmann::json specs = nlohmann::json::array();
  if (flight.fault_case != nullptr)
    for (const auto& f : flight.fault_case->faults) specs.push_back(f.text());
  j["flight"] = {{"campaign", campaign.name},
                 {"index", flight.index},
                 {"id", flight.id},
                 {"name", flight.name},
                 {"trajectory", flight.trajectory != nullptr ? flight.trajectory->as_written : ""},
                 {"fault_case", flight.fault_case != nullptr ? flight.fault_case->name : ""},
                 {"faults", specs},
                 {"seed", flight.seed},
                 {"speed", flight.speed}};
  return j;
}

const nlohmann::json* figure_at(const nlohmann::json& summary, const std::string& path) {
  const nlohmann::json* node = &summary;
  std::size_t from = 0;
  while (from <= path.size()) {
    const std::size_t dot = path.find('.', from);
    const std::string part = path.substr(from, dot == std::string::npos ? std::string::npos : dot - from);
    if (!node->is_object()) return nullptr;
    const auto it = node->find(part);
    if (it == node->end()) return nullptr;
    node = &*it;
    if (dot == std::string::npos) return node;
    from = dot + 1;
  }
  return nullptr;
}

std::string summary_line(const Flight& flight, const nlohmann::json& summary) {
  auto number = [&](const char* path, const char* format) -> std::string {
    const auto* v = figure_at(summary, path);
    if (v == nullptr || !v->is_number()) return "n/a";
    char text[48];
    std::snprintf(text, sizeof text, format, v->get<double>());
    return text;
  };
  const auto* state = figure_at(summary, "trajectory.state");
  std::string line = flight.name + ": ended " + summary.value("end", std::string("?"));
  if (state != nullptr && state->is_string()) line += " (trajectory " + state->get<std::string>() + ")";
  line += ", tracking RMS " + number("trajectory.rms_m", "%.3f m") + " max " + number("trajectory.max_m", "%.3f m");
  line += ", touchdowns " + number("landing.touchdowns", "%.0f");
  line += ", loop latency p99 " + number("loop_latency.p99_us", "%.0f us");
  line += "; " + number("sim_time_s", "%.1f s") + " simulated in " + number("wall_time_s", "%.2f s");
  return line;
}

}  // namespace hitl::campaign
