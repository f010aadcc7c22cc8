// hitl sim: the Simbody x500 bridged to a flight stack over MAVLink (replaces the spec's
// Gazebo + mavlink_hitl_gazebosim + hitl-gz-start.sh).
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include <unistd.h>

#include "cli/adb_options.h"
#include "cli/commands.h"
#include "cli/number_check.h"
#include "cli/session_dashboard.h"
#include "engine/hil/session.h"
#include "engine/net/socket_address.h"
#include "engine/vehicle/trajectory.h"
#include "engine/model/config_json.h"
#include "engine/model/x500_defaults.h"
#include "tui/terminal.h"

namespace hitl::cli {
namespace {

struct SimOptions {
  hil::SessionConfig session;
  std::string vehicle_file;
  std::string world_file;
  std::string trajectory_file;
  bool tui = false;  ///< --tui: the dashboard (docs/tui.md)
  std::string px4_sitl;  ///< "tcp:4560" / "udp:14560" when --px4-sitl is given
  bool px4_sitl_given = false;
  AdbOptions adb;  ///< --adb, --adb-serial, --adb-relay: the board through adb (docs/adb.md)
  bool no_vio = false;
  std::optional<bool> en_vio_output;
  std::string protocol_version = "2.0";
  int sysid = hil::kSimulatorSystemId;
  int compid = hil::kSimulatorComponentId;
};

nlohmann::json streams_json(const std::map<std::string, hil::StreamCount>& streams, double wall_s) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, c] : streams)
    j[name] = {{"count", c.count}, {"rate_hz", wall_s > 0 ? static_cast<double>(c.count) / wall_s : 0.0}};
  return j;
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
  if (final_summary) {
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
  return line;
}

class SimPrinter : public hil::Session::Observer {
 public:
  explicit SimPrinter(const GlobalOptions& global) : global_(global), tty_(::isatty(STDERR_FILENO) == 1) {}
  void on_event(const hil::SessionEvent& e) override {
    end_line();
    const char* prefix = e.severity == hil::Severity::Warning ? "warning: " : (e.severity == hil::Severity::Error ? "error: " : "");
    if (e.severity != hil::Severity::Info || !global_.quiet) std::cerr << "hitl sim: " << prefix << e.text << '\n';
  }
  void on_status(const hil::SessionSnapshot& s) override {
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
  void end_line() {
    if (pending_) std::cerr << '\n';
    pending_ = false;
  }

 private:
  const GlobalOptions& global_;
  bool tty_;
  bool pending_ = false;
};

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
  if (!s.trajectory_state.empty())
    std::printf("trajectory: %s%s, tracking error against truth RMS %.2f m, max %.2f m (%llu samples)\n",
                s.trajectory_state.c_str(), s.trajectory_failure.empty() ? "" : (": " + s.trajectory_failure).c_str(),
                s.trajectory_rms_m, s.trajectory_max_m, static_cast<unsigned long long>(s.trajectory_samples));
}

int run_sim(const GlobalOptions& global, SimOptions& opt) {
  const std::string cmd = "sim";
  auto& cfg = opt.session;
  if (opt.tui) {
    if (auto usable = tui::terminal_usable(); !usable) {
      std::cerr << "hitl sim: --tui: " << usable.error().message << "; showing the status lines instead\n";
      opt.tui = false;
    }
  }
  auto vehicle = opt.vehicle_file.empty() ? Expected<model::VehicleConfig>(model::x500_vehicle_config())
                                          : model::load_vehicle_config(opt.vehicle_file);
  if (!vehicle) {
    log_error(cmd, "--vehicle: " + vehicle.error().message);
    return kExitUsage;
  }
  auto world = opt.world_file.empty() ? Expected<model::WorldConfig>(model::default_world_config())
                                      : model::load_world_config(opt.world_file);
  if (!world) {
    log_error(cmd, "--world: " + world.error().message);
    return kExitUsage;
  }
  std::optional<vehicle::Trajectory> for_f_key;  // with the dashboard the trajectory waits for the f key
  if (!opt.trajectory_file.empty()) {
    auto trajectory = vehicle::Trajectory::load(opt.trajectory_file);
    if (!trajectory) {
      log_error(cmd, "-t: " + trajectory.error().message);
      return kExitUsage;
    }
    if (opt.tui) for_f_key = std::move(trajectory.value());
    else cfg.trajectory = std::move(trajectory.value());
  }
  cfg.vehicle = *vehicle;
  cfg.world = *world;
  cfg.sysid = static_cast<uint8_t>(opt.sysid);
  cfg.compid = static_cast<uint8_t>(opt.compid);
  cfg.protocol = opt.protocol_version == "1.0" ? mavlink::Version::V1 : mavlink::Version::V2;
  if (opt.no_vio) cfg.vio = false;
  if (opt.en_vio_output) cfg.vio = *opt.en_vio_output;
  if (opt.px4_sitl_given) {
    const std::string& spec = opt.px4_sitl.empty() ? "tcp:4560" : opt.px4_sitl;
    const auto colon = spec.find(':');
    const std::string kind = spec.substr(0, colon);
    if (colon == std::string::npos || (kind != "tcp" && kind != "udp")) {
      log_error(cmd, "--px4-sitl: '" + spec + "' is not tcp:PORT or udp:PORT");
      return kExitUsage;
    }
    auto port = net::parse_port(spec.substr(colon + 1), "--px4-sitl");
    if (!port) {
      log_error(cmd, port.error().message);
      return kExitUsage;
    }
    cfg.link = kind == "tcp" ? hil::FlightStackLink::SitlTcp : hil::FlightStackLink::SitlUdp;
    cfg.sitl_port = *port;
  }
  if (cfg.local_port != 0 && cfg.local_port == cfg.clients_port &&
      (cfg.bind_address == "0.0.0.0" || cfg.bind_address == cfg.clients_bind)) {
    // Both would bind the same UDP port: the second bind failed with "another process is bound
    // there", which sent the user looking for a process that was this one.
    log_error(cmd, "--clients " + std::to_string(cfg.clients_port) + " is also the --local-port of the HIL link; give them different ports");
    return kExitUsage;
  }
  if (cfg.local_port == 0)
    std::cerr << "hitl sim: warning: --local-port 0 picks an ephemeral port; a PX4 instance keeps the first port it "
                 "heard, so a later session on another port gets no answer\n";

  // --adb: the board's HIL and VIO ports are the tunnel's local endpoints (docs/adb.md).
  std::unique_ptr<net::AdbTunnel> tunnel;
  if (opt.adb.enabled()) {
    auto opened = open_adb_tunnel(global, cmd, opt.adb);
    if (!opened) {
      log_error(cmd, "--adb: " + opened.error().message);
      return kExitFailed;
    }
    tunnel = std::move(opened.value());
    log_info(global, "hitl sim: " + tunnel->describe());
    cfg.target_ip = "127.0.0.1";
    cfg.hil_port = tunnel->local_endpoint(adb::Channel::Hil).port();
    cfg.vio_ip = "127.0.0.1";
    cfg.vio_port = tunnel->local_endpoint(adb::Channel::Vio).port();
  }

  auto session = hil::Session::create(cfg);
  if (!session) {
    log_error(cmd, session.error().message);
    return kExitUsage;
  }
  const auto& stop = stop_flag_on_signals();
  log_info(global, "hitl sim: " + (*session)->describe() + (opt.tui ? "" : " (Ctrl-C to stop)"));
  Expected<hil::Session::EndReason> end = Error{"not run"};
  if (opt.tui) {
    tui::SimDashboardConfig dc;
    dc.trajectory_file = opt.trajectory_file;
    dc.trajectory = std::move(for_f_key);
    dc.trajectory_mode = opt.session.trajectory_mode;
    end = run_session_with_dashboard(global, cmd, **session, opt.session, dc);
  } else {
    SimPrinter printer(global);
    end = (*session)->run(stop, printer);
    printer.end_line();
  }
  const auto snap = (*session)->snapshot();
  if (!end) {
    log_error(cmd, end.error().message);
    if (global.json) {
      auto j = snapshot_json(snap, true);
      j["end"] = "error";
      j["error"] = end.error().message;
      if (tunnel) j["adb"] = adb_tunnel_json(*tunnel);
      print_json_line(j);
    }
    return kExitFailed;
  }
  if (global.json) {
    auto j = snapshot_json(snap, true);
    j["end"] = end_reason_name(*end);
    if (tunnel) j["adb"] = adb_tunnel_json(*tunnel);
    print_json_line(j);
  } else {
    print_summary(snap, end_reason_name(*end));
    if (tunnel) std::printf("%s\n", adb_tunnel_line(*tunnel).c_str());
  }
  if (!snap.record_error.empty()) log_error(cmd, "--record: " + snap.record_error + "; the recording is incomplete");
  // Every send refused: the session ran, but nothing it simulated reached anyone.
  uint64_t delivered = 0;
  for (const auto& [name, c] : snap.sent) delivered += c.count;
  if (snap.send_errors > 0 && delivered == 0) {
    log_error(cmd, "nothing was delivered: all " + std::to_string(snap.send_errors) + " messages failed to send (" +
                       snap.last_send_error + ")");
    return kExitFailed;
  }
  const bool failed = *end == hil::Session::EndReason::FlightStackGone || *end == hil::Session::EndReason::TrajectoryFailed ||
                      !snap.record_error.empty();
  return failed ? kExitFailed : kExitOk;
}

}  // namespace

void add_sim_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto opt = std::make_shared<SimOptions>();
  auto& c = opt->session;
  auto* sub = app.add_subcommand("sim", "Simulate the x500 and bridge it to the board (or PX4 SITL) over MAVLink");
  sub->footer(
      "Examples:\n"
      "  hitl sim --adb                    # board over USB through adb (hitl-adb-relay; docs/adb.md)\n"
      "  hitl sim -i 192.168.101.2         # board over USB-Ethernet\n"
      "  hitl sim --px4-sitl               # PX4 SITL connects to TCP 4560 (lockstep)\n"
      "  hitl sim --duration 60 --json     # headless, a JSON summary at the end\n"
      "Names of the spec's SDF plugin parameters work too (--mavlink-addr, --vio-update-rate, ...).");
  const char* link = "Board link";
  sub->add_option("-i,--target-ip,--mavlink-addr", c.target_ip, "The board's IP (USB-Ethernet; --adb reaches it through adb instead)")
      ->capture_default_str()->group(link);
  sub->add_option("--hil-port,--mavlink-udp-remote-port", c.hil_port, "The board's HIL MAVLink port")
      ->capture_default_str()->check(number_in(1, 65535))->group(link);
  sub->add_option("--local-port,--mavlink-udp-local-port", c.local_port,
                  "Fixed local port: PX4 keeps answering the first port it heard")
      ->capture_default_str()->check(number_in(0, 65535))->group(link);
  sub->add_option("--bind", c.bind_address, "Local address for the simulator's sockets")->capture_default_str()->group(link);
  auto* px4_sitl = sub->add_option("--px4-sitl", opt->px4_sitl,
                                   "Serve PX4 SITL's simulator_mavlink instead of a board: tcp:PORT (hitl listens, "
                                   "default tcp:4560) or udp:PORT")
                       ->expected(0, 1)->type_name("[tcp:4560|udp:PORT]")->group(link);
  sub->add_option("--sysid", opt->sysid, "System id of the simulator's HEARTBEAT and frames")
      ->capture_default_str()->check(number_in(1, 255))->group(link);
  sub->add_option("--compid", opt->compid, "Component id of the simulator")->capture_default_str()->check(number_in(1, 255))->group(link);
  sub->add_option("--protocol-version", opt->protocol_version, "MAVLink protocol version")
      ->capture_default_str()->check(CLI::IsMember({"1.0", "2.0"}))->group(link);
  add_adb_options(*sub, opt->adb, link);

  const char* vio = "VIO (ODOMETRY from ground truth)";
  sub->add_option("--vio-ip,--vio-mavlink-addr", c.vio_ip, "Where voxl-hitl-vio-server listens (default: the target IP)")->group(vio);
  sub->add_option("--vio-port,--vio-udp-remote-port", c.vio_port, "VIO port")->capture_default_str()->check(number_in(1, 65535))->group(vio);
  sub->add_option("--vio-rate,--vio-update-rate", c.vio_rate_hz, "ODOMETRY rate, Hz")->capture_default_str()->check(positive_number())->group(vio);
  sub->add_flag("--no-vio", opt->no_vio, "Send no ODOMETRY")->group(vio);
  sub->add_option("--en-vio-output", opt->en_vio_output, "Send ODOMETRY (true/false; the spec's en_vio_output)")->group(vio);

  const char* timing = "Timing";
  sub->add_option("--speed", c.speed, "Real-time factor to hold; 0 = as fast as possible")
      ->capture_default_str()->check(non_negative_number())->group(timing);
  sub->add_option("--duration", c.duration_s, "Stop after this many simulated seconds (0: until Ctrl-C)")
      ->capture_default_str()->check(non_negative_number())->type_name("S")->group(timing);
  sub->add_flag("--lockstep,--enable-lockstep", c.lockstep,
                "Step only after the flight stack answered the previous sensors (a board over UDP: paces the simulator)")
      ->group(timing);
  sub->add_option("--lockstep-timeout", c.lockstep_timeout_s, "How long lockstep waits for an answer before stepping on, s")
      ->capture_default_str()->check(positive_number())->group(timing);
  sub->add_option("--actuator-timeout", c.actuator_timeout_s, "Motors stop when no HIL_ACTUATOR_CONTROLS came for this long, s")
      ->capture_default_str()->check(positive_number())->group(timing);
  sub->add_flag("--realtime", c.realtime, "Ask for SCHED_FIFO and mlockall (says so when not permitted)")->group(timing);

  const char* model = "Model";
  sub->add_option("--vehicle", opt->vehicle_file, "Vehicle JSON over the compiled-in x500 (docs/engine.md)")
      ->check(CLI::ExistingFile)->group(model);
  sub->add_option("--world", opt->world_file, "World JSON: home, magnetic field, wind (docs/engine.md)")
      ->check(CLI::ExistingFile)->group(model);
  // "-1" is refused by the check every unsigned option gets (cli/number_check.h), not wrapped to 2^64 - 1.
  sub->add_option("--seed", c.seed, "Noise and gust seed (runs repeat)")
      ->capture_default_str()
      ->group(model);
  sub->add_flag("--no-noise", [opt](int64_t) { opt->session.noise = false; },
                "Noise-free sensors (tests only: PX4 marks repeating values stale and refuses to arm)")
      ->group(model);

  sub->add_option("-t,--trajectory", opt->trajectory_file,
                  "Fly this trajectory file (the spec's trajectory_rc: arm, take off, follow the waypoints by stick, "
                  "hold, land) and end the session; the summary gives the tracking error against ground truth. With --tui: "
                  "flown when you press f, through the client port")
      ->check(CLI::ExistingFile)->type_name("FILE.json")->group(model);
  sub->add_option("--trajectory-mode", c.trajectory_mode,
                  "-t's sticks: velocity (Position mode) or attitude (Stabilized: tilt and thrust)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, vehicle::StickMode>{{"velocity", vehicle::StickMode::Velocity},
                                                                                  {"attitude", vehicle::StickMode::Attitude}}))
      ->default_str("velocity")->group(model);

  sub->add_flag("--tui", opt->tui,
                "The live dashboard (docs/tui.md): data paths, dsp_hitl, EKF, vehicle, messages, link; keys a arm, d disarm, "
                "t takeoff, l land, p pause, r reset, f fly the -t file (waits for the key), s shell, ? help, q quit. "
                "Without a terminal: the status lines")
      ->group("Dashboard");

  const char* route = "Clients and recording";
  sub->add_option("--clients", c.clients_port, "UDP port on 127.0.0.1 for local MAVLink clients (other hitl commands); 0: none")
      ->capture_default_str()->check(number_in(0, 65535))->group(route);
  sub->add_option("--gcs", c.gcs, "Also route the board's telemetry to a ground station (QGroundControl: 127.0.0.1:14550)")
      ->type_name("HOST:PORT")->group(route);
  sub->add_option("--truth-rate", c.truth_rate_hz,
                  "Ground truth to clients as ODOMETRY (sysid " + std::to_string(hil::kSimulatorSystemId) +
                      ", estimator MOCAP), Hz; 0: none")
      ->capture_default_str()->check(non_negative_number())->group(route);
  sub->add_option("--record", c.record_path, "Save everything sent and received to a .tlog")->type_name("FILE.tlog")->group(route);
  // Through adb the board's ports are the relay's; an address for them would be ignored.
  for (const char* adb_name : {"--adb", "--adb-serial"})
    for (const char* other : {"--target-ip", "--hil-port", "--vio-ip", "--vio-port", "--px4-sitl"})
      sub->get_option(adb_name)->excludes(sub->get_option(other));
  sub->callback([&options, &state, opt, px4_sitl]() {
    opt->px4_sitl_given = px4_sitl->count() > 0;  // also when given bare: `--px4-sitl` means tcp:4560
    state.exit_code = run_sim(options, *opt);
  });
}

}  // namespace hitl::cli
