#include "cli/sim_output.h"

#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <map>


namespace hitl::cli {

nlohmann::json fault_event_json(const faults::FaultChange& change) {
  return {{"type", "status"},
          {"fault",
           {{"event", change.refused ? "refused" : change.started ? "started" : "ended"},
            {"name", change.spec.name()},
            {"args", change.spec.args},
            {"sim_time_s", change.t_s},
            {"duration_s", change.spec.duration_s ? nlohmann::json(*change.spec.duration_s) : nlohmann::json(nullptr)}}}};
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
