#include "engine/hil/snapshot_json.h"

#include <map>

#include "engine/telemetry/latency_json.h"

namespace hitl::hil {

namespace {

nlohmann::json streams_json(const std::map<std::string, StreamCount>& streams, double wall_s) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, c] : streams)
    j[name] = {{"count", c.count}, {"rate_hz", wall_s > 0 ? static_cast<double>(c.count) / wall_s : 0.0}};
  return j;
}

nlohmann::json loop_latency_json(const LoopLatencySummary& l, bool with_histogram) {
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

nlohmann::json snapshot_json(const SessionSnapshot& s, bool final_summary) {
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
  if (!s.board_timing.empty()) {
    const auto& f = s.board_timing_figures;
    j["board_timing"] = {{"model", s.board_timing},
                         {"imu_samples", f.imu_samples},
                         {"imu_delay_mean_ms", f.imu_delay_mean_s * 1e3},
                         {"imu_delay_max_ms", f.imu_delay_max_s * 1e3},
                         {"mag_baro_samples", f.mag_baro_samples},
                         {"mag_baro_delay_mean_ms", f.mag_baro_delay_mean_s * 1e3},
                         {"mag_baro_delay_max_ms", f.mag_baro_delay_max_s * 1e3}};
  }
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
  auto link_json = [](const LinkFaultCounts& c) {
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

}  // namespace hitl::hil
