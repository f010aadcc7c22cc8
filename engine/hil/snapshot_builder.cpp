#include "engine/hil/snapshot_builder.h"

#include "engine/frames/frames.h"

namespace hitl::hil {
namespace {

std::map<std::string, StreamCount> by_name(const std::map<uint32_t, StreamCounter>& counters,
                                           const mavlink::MessageSet& messages) {
  std::map<std::string, StreamCount> out;
  for (const auto& [id, c] : counters) {
    const auto* d = messages.find(id);
    out[d ? d->name : "?"] = StreamCount{c.count, c.rate_hz};
  }
  return out;
}

}  // namespace

SessionSnapshot make_snapshot(const SnapshotSources& in) {
  SessionSnapshot s;
  const auto& st = in.state;
  s.sim_time_s = in.sim_time_s;
  s.wall_time_s = in.wall_time_s;
  s.real_time_factor = s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0;
  s.recent_real_time_factor = in.recent_real_time_factor;
  s.sent = by_name(in.traffic.sent, in.messages);
  s.received = by_name(in.traffic.received, in.messages);
  s.send_errors = in.traffic.send_errors;
  s.last_send_error = in.traffic.last_send_error;

  const auto& link = in.stack.link();
  const auto& actuators = in.stack.actuators();
  s.connected = in.stack.connected();  // a stream: connected; a datagram link: the answers arriving
  if (link.peer()) s.partner = link.peer()->to_string();
  s.armed = actuators.armed();
  s.motor_commands = actuators.last_controls();
  s.rotor_speed_rad_s = st.rotor_speed_rad_s;

  // Truth from home at rest, the origin PX4's local position uses.
  const Eigen::Vector3d p_home_ENU_m = st.p_ENU_m - Eigen::Vector3d(0, 0, in.rest_altitude_m);
  const Eigen::Vector3d p_home_NED_m = frames::enu_to_ned(p_home_ENU_m);
  s.altitude_m = p_home_ENU_m.z();
  s.p_NED_m = {p_home_NED_m.x(), p_home_NED_m.y(), p_home_NED_m.z()};
  const Eigen::Quaterniond q = frames::q_FRD_to_NED_from(st.q_FLU_to_ENU);
  s.q_FRD_to_NED = {q.w(), q.x(), q.y(), q.z()};
  s.on_ground = st.on_ground;
  s.steps = st.step;

  s.late_ticks = in.pacer.late;
  s.resyncs = in.pacer.resyncs;
  s.max_lateness_ms = in.pacer.max_lateness_s * 1000.0;
  s.actuator_clamped = actuators.counters().clamped;
  s.ignored_other_address = link.stats().ignored_other_address;
  s.ignored_other_sysid = actuators.counters().ignored_sysid;
  s.actuator_timeouts = actuators.counters().timeouts;
  s.lockstep_waits = in.stack.lockstep_counters().waits;
  s.lockstep_fallbacks = in.stack.lockstep_counters().fallbacks;
  s.lockstep_late_answers = actuators.counters().late;
  s.lockstep_foreign_clock = actuators.counters().foreign_clock;
  s.imu_accel_saturated = in.sensors.imu().saturation().accel;
  s.imu_gyro_saturated = in.sensors.imu().saturation().gyro;
  if (const auto& timing = in.sensors.data_path_timing()) {
    s.board_timing = in.config.board_timing;
    s.board_timing_figures = timing->figures();
  }
  const auto& td = in.touchdowns.stats();
  s.touchdowns = td.touchdowns;
  s.max_rebound_m = td.max_rebound_m;
  s.max_touchdown_speed_m_s = td.max_touchdown_speed_m_s;
  s.peak_touchdown_accel_m_s2 = td.peak_accel_m_s2;
  s.crc_errors = in.stack.parser_stats().crc_errors;
  s.parse_errors = in.stack.parser_stats().parse_errors;

  s.clients = in.clients.client_count();
  s.clients_refused = in.clients.clients_refused();
  s.client_frames_dropped = in.clients.client_frames_dropped();
  s.routed_to_board = in.stack.routed_to_board();
  s.routed_to_clients = in.clients.routed_to_clients();
  if (in.pilot) {
    s.trajectory_state = vehicle::to_string(in.pilot->state());
    s.trajectory_failure = in.pilot->failure();
    const auto t = in.pilot->tracking();
    s.trajectory_samples = t.samples;
    s.trajectory_rms_m = t.rms_m;
    s.trajectory_max_m = t.max_m;
  }
  s.actuator_flags = actuators.last_flags();
  s.actuator_mode = actuators.last_mode();
  s.paths = in.paths;
  s.paused = in.paused;
  s.resets = in.resets;
  s.speed = in.config.speed;
  s.lockstep = in.stack.lockstep();
  s.record_error = in.record_error;
  return s;
}

}  // namespace hitl::hil
