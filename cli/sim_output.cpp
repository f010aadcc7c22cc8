#include "cli/sim_output.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <map>

#include "engine/telemetry/latency_json.h"

namespace hitl::cli {

namespace {

nlohmann::json streams_json(const std::map<std::string, hil::StreamCount>& streams, double wall_s) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, c] : streams)
    j[name] = {{"count", c.count}, {"rate_hz", wall_s > 0 ? static_cast<double>(c.count) / wall_s : 0.0}};
  return j;
}

nlohmann::json loop_latency_json(const hil::LoopLatencySummary& l, bool with_histogram) {
  auto j = telemetry::to_json(l.latency, with_histogram);
  j["matched"] = l.lockstep ? "echo" : "next";
  j["sensors"] = l.sensors;
  j["unanswered"] = l.unanswered;
  return j;
}

nlohmann::json fault_records_json(const std::vector<faults::FaultRecord>& records) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& r : records)
    j.push_back({{"name", r.name},
                 {"args", r.args},
                 {"start_s", r.start_s},
                 {"end_s", r.end_s ? nlohmann::json(*r.end_s) : nlohmann::json(nullptr)}});
  return j;
}

}  // namespace

nlohmann::json fault_event_json(const faults::FaultChange& change) {
  return {{"type", "status"},
          {"fault",
           {{"event", change.refused ? "refused" : change.started ? "started" : "ended"},
            {"name", change.spec.name()},
            {"args", change.spec.args},
            {"sim_time_s", change.t_s},
            {"duration_s", change.spec.duration_s ? nlohmann::json(*change.spec.duration_s) : nlohmann::json(nullptr)}}}};
}

nlohmann::json snapshot_json(const hil::SessionSnapshot& s, bool final_summary) {
  nlohmann::json j;
  j["type"] = final_summary ? "summary" : "status";
  j["sim_time_s"] = s.sim_time_s;
  j["wall_time_s"] = s.wall_time_s;
  j["real_time_factor"] = s.real_time_factor;
  j["recent_real_time_factor"] = s.recent_real_time_factor;
  j["connected"] = s.connected;
  j["partner"] = s.partner;
  j["armed"] = s.armed;
  j["altitude_m"] = s.altitude_m;
  j["position_ned_m"] = s.p_NED_m;
  j["motor_commands"] = s.motor_commands;
  j["rotor_speed_rad_s"] = s.rotor_speed_rad_s;
  j["steps"] = s.steps;
  j["late_ticks"] = s.late_ticks;
  j["resyncs"] = s.resyncs;
  j["max_lateness_ms"] = s.max_lateness_ms;
  j["clamped"] = s.actuator_clamped;
  j["ignored"] = {{"other_address", s.ignored_other_address}, {"other_sysid", s.ignored_other_sysid}};
  j["actuator_timeouts"] = s.actuator_timeouts;
  j["actuator_flags"] = s.actuator_flags;
  j["actuator_mode"] = s.actuator_mode;
  j["lockstep"] = {{"waits", s.lockstep_waits},
                   {"fallbacks", s.lockstep_fallbacks},
                   {"late_answers", s.lockstep_late_answers},
                   {"foreign_clock", s.lockstep_foreign_clock}};
  j["imu_saturated"] = {{"accel", s.imu_accel_saturated}, {"gyro", s.imu_gyro_saturated}};
  j["landing"] = {{"touchdowns", s.touchdowns},
                  {"max_rebound_m", s.max_rebound_m},
                  {"max_touchdown_speed_m_s", s.max_touchdown_speed_m_s},
                  {"peak_accel_m_s2", s.peak_touchdown_accel_m_s2}};
  if (s.px4.instance >= 0)
    j["px4"] = {{"instance", s.px4.instance}, {"version", s.px4.version}, {"build", s.px4.build_dir},
                {"work_dir", s.px4.work_dir}, {"console", s.px4.console}};
  j["send_errors"] = s.send_errors;
  j["send_error"] = s.last_send_error;
  j["crc_errors"] = s.crc_errors;
  j["parse_errors"] = s.parse_errors;
  j["clients"] = s.clients;
  if (!s.record_error.empty()) j["record_error"] = s.record_error;
  j["clients_refused"] = s.clients_refused;
  j["client_frames_dropped"] = s.client_frames_dropped;
  j["routed"] = {{"to_board", s.routed_to_board}, {"to_clients", s.routed_to_clients}};
  if (!s.trajectory_state.empty())
    j["trajectory"] = {{"state", s.trajectory_state},
                       {"failure", s.trajectory_failure},
                       {"samples", s.trajectory_samples},
                       {"rms_m", s.trajectory_rms_m},
                       {"max_m", s.trajectory_max_m}};
  j["active_faults"] = s.active_faults;
  j["faults_not_started"] = s.pending_faults;
  auto link_json = [](const hil::LinkFaultCounts& c) {
    return nlohmann::json{{"dropped_datagrams", c.dropped}, {"delayed_datagrams", c.delayed},
                          {"reordered_datagrams", c.reordered}, {"duplicated_datagrams", c.duplicated}};
  };
  j["hil_link_faults"] = link_json(s.hil_link_faults);
  j["vio_link_faults"] = link_json(s.vio_link_faults);
  j["loop_latency"] = loop_latency_json(s.loop_latency, final_summary);
  if (final_summary) {
    j["faults"] = fault_records_json(s.faults);
    j["sent"] = streams_json(s.sent, s.wall_time_s);
    j["received"] = streams_json(s.received, s.wall_time_s);
  } else {
    nlohmann::json out = nlohmann::json::object(), in = nlohmann::json::object();
    for (const auto& [name, c] : s.sent) out[name] = {{"count", c.count}, {"rate_hz", c.rate_hz}};
    for (const auto& [name, c] : s.received) in[name] = {{"count", c.count}, {"rate_hz", c.rate_hz}};
    j["sent"] = out;
    j["received"] = in;
  }
  return j;
}

std::string status_line(const hil::SessionSnapshot& s) {
  auto rate = [](const std::map<std::string, hil::StreamCount>& m, const char* name) {
    auto it = m.find(name);
    return it == m.end() ? 0.0 : it->second.rate_hz;
  };
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "t %7.1f s  rtf %4.2f  out HIL_SENSOR %3.0f GPS %2.0f ODOM %3.0f Hz  in ACT %3.0f Hz  %s  alt %6.2f m  late %llu",
                s.sim_time_s, s.recent_real_time_factor, rate(s.sent, "HIL_SENSOR"), rate(s.sent, "HIL_GPS"),
                rate(s.sent, "ODOMETRY"), rate(s.received, "HIL_ACTUATOR_CONTROLS"), s.armed ? "ARMED   " : "disarmed",
                s.altitude_m, static_cast<unsigned long long>(s.late_ticks));
  std::string line = buf;
  if (s.imu_accel_saturated + s.imu_gyro_saturated > 0) {
    std::snprintf(buf, sizeof buf, "  IMU SAT %llu", static_cast<unsigned long long>(s.imu_accel_saturated + s.imu_gyro_saturated));
    line += buf;
  }
  if (s.send_errors > 0) line += "  SEND ERRORS " + std::to_string(s.send_errors);
  if (!s.active_faults.empty()) {
    line += "  FAULTS";
    for (const auto& f : s.active_faults) line += " " + f;
  }
  return line;
}

void print_summary(const hil::SessionSnapshot& s, const char* end) {
  std::printf("\nsim %.1f s in %.1f s wall (real-time factor %.2f), %llu steps, ended: %s\n", s.sim_time_s, s.wall_time_s,
              s.real_time_factor, static_cast<unsigned long long>(s.steps), end);
  std::printf("%-24s %10s %10s\n", "SENT", "COUNT", "RATE Hz");
  for (const auto& [name, c] : s.sent)
    std::printf("%-24s %10llu %10.1f\n", name.c_str(), static_cast<unsigned long long>(c.count),
                s.wall_time_s > 0 ? static_cast<double>(c.count) / s.wall_time_s : 0.0);
  std::printf("%-24s %10s %10s\n", "RECEIVED", "COUNT", "RATE Hz");
  for (const auto& [name, c] : s.received)
    std::printf("%-24s %10llu %10.1f\n", name.c_str(), static_cast<unsigned long long>(c.count),
                s.wall_time_s > 0 ? static_cast<double>(c.count) / s.wall_time_s : 0.0);
  if (s.received.empty()) std::printf("(nothing received from the flight stack)\n");
  if (s.send_errors > 0)
    std::printf("send errors %llu (not counted as sent): %s\n", static_cast<unsigned long long>(s.send_errors),
                s.last_send_error.c_str());
  std::printf("late ticks %llu (max %.1f ms late, %llu resyncs)  clamped %llu  ignored: other address %llu, other sysid %llu"
              "  actuator timeouts %llu  lockstep fallbacks %llu\n",
              static_cast<unsigned long long>(s.late_ticks), s.max_lateness_ms, static_cast<unsigned long long>(s.resyncs),
              static_cast<unsigned long long>(s.actuator_clamped), static_cast<unsigned long long>(s.ignored_other_address),
              static_cast<unsigned long long>(s.ignored_other_sysid), static_cast<unsigned long long>(s.actuator_timeouts),
              static_cast<unsigned long long>(s.lockstep_fallbacks));
  std::printf("final position NED (%.2f, %.2f, %.2f) m, %s\n", s.p_NED_m[0], s.p_NED_m[1], s.p_NED_m[2],
              s.armed ? "armed" : "disarmed");
  std::printf("touchdowns %llu (fastest %.2f m/s, peak %.1f g, max rebound %.3f m)  IMU saturated: accel %llu, gyro %llu"
              "  lockstep late answers %llu\n",
              static_cast<unsigned long long>(s.touchdowns), s.max_touchdown_speed_m_s, s.peak_touchdown_accel_m_s2 / 9.80665,
              s.max_rebound_m, static_cast<unsigned long long>(s.imu_accel_saturated),
              static_cast<unsigned long long>(s.imu_gyro_saturated), static_cast<unsigned long long>(s.lockstep_late_answers));
  for (const auto& r : s.faults) {
    const std::string given = r.text();  // as the status lines and --fault write it: motor:2,0.6
    if (r.end_s) std::printf("fault %s: %.3f s to %.3f s\n", given.c_str(), r.start_s, *r.end_s);
    else std::printf("fault %s: from %.3f s to the end\n", given.c_str(), r.start_s);
  }
  for (const auto& f : s.pending_faults) std::printf("fault %s: never started\n", f.c_str());
  for (const auto& [name, c] : {std::pair{"HIL", s.hil_link_faults}, std::pair{"VIO", s.vio_link_faults}})
    if (c.dropped + c.delayed + c.reordered + c.duplicated > 0)
      std::printf("%s link faults: %llu datagrams dropped, %llu delayed, %llu reordered, %llu duplicated\n", name,
                  static_cast<unsigned long long>(c.dropped), static_cast<unsigned long long>(c.delayed),
                  static_cast<unsigned long long>(c.reordered), static_cast<unsigned long long>(c.duplicated));
  if (const auto& l = s.loop_latency.latency; l.count > 0)
    std::printf("loop latency (HIL_SENSOR -> %s HIL_ACTUATOR_CONTROLS, %llu answered): p50 %.2f ms  p95 %.2f ms  p99 %.2f ms"
                "  max %.2f ms\n",
                s.loop_latency.lockstep ? "its" : "the next", static_cast<unsigned long long>(l.count), l.p50_us / 1000,
                l.p95_us / 1000, l.p99_us / 1000, l.max_us / 1000);
  if (!s.trajectory_state.empty())
    std::printf("trajectory: %s%s, tracking error against truth RMS %.2f m, max %.2f m (%llu samples)\n",
                s.trajectory_state.c_str(), s.trajectory_failure.empty() ? "" : (": " + s.trajectory_failure).c_str(),
                s.trajectory_rms_m, s.trajectory_max_m, static_cast<unsigned long long>(s.trajectory_samples));
}

SimPrinter::SimPrinter(const GlobalOptions& global) : global_(global), tty_(::isatty(STDERR_FILENO) == 1) {}

void SimPrinter::on_event(const hil::SessionEvent& e) {
  end_line();
  const char* prefix = e.severity == hil::Severity::Warning ? "warning: " : (e.severity == hil::Severity::Error ? "error: " : "");
  if (e.severity != hil::Severity::Info || !global_.quiet) std::cerr << "hitl sim: " << prefix << e.text << '\n';
  if (e.fault && global_.json) print_json_line(fault_event_json(*e.fault));
}

void SimPrinter::on_status(const hil::SessionSnapshot& s) {
  if (global_.json) {
    print_json_line(snapshot_json(s, false));
    return;
  }
  if (global_.quiet) return;
  if (tty_) {
    std::cerr << '\r' << status_line(s) << "\x1b[K" << std::flush;
    pending_ = true;
  } else {
    std::cerr << status_line(s) << '\n';
  }
}

void SimPrinter::end_line() {
  if (pending_) std::cerr << '\n';
  pending_ = false;
}

}  // namespace hitl::cli
