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
#include "cli/parse_errors.h"
#include "cli/session_dashboard.h"
#include "cli/report_output.h"
#include "cli/sim_output.h"
#include "cli/value_types.h"
#include "engine/faults/fault_schedule.h"
#include "engine/faults/scenario.h"
#include "engine/hil/session.h"
#include "engine/hil/stack_peer.h"
#include "engine/px4/px4_build.h"
#include "engine/px4/px4_process.h"
#include "engine/vehicle/trajectory.h"
#include "engine/model/config_json.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/data_path_timing.h"
#include "engine/sensors/vehicle_file.h"
#include "tui/terminal.h"

namespace hitl::cli {
namespace {

struct SimOptions {
  hil::SessionConfig session;
  std::string vehicle_file;
  std::string world_file;
  std::string trajectory_file;
  bool tui = false;  ///< --tui: the dashboard (docs/tui.md)
  std::string px4_sitl;  ///< "tcpin:4560" / "udp:HOST:PORT" when --px4-sitl is given (bare: tcpin:4560)
  bool px4_sitl_given = false;
  std::string px4_dir;                   ///< --px4 DIR: PX4 SITL that hitl starts (engine/hil/px4_launch.h)
  std::vector<std::string> px4_params;   ///< --px4-param NAME=VALUE, repeatable
  std::optional<double> px4_speed;       ///< --px4-speed K
  double px4_timeout_s = 30;             ///< --px4-timeout S
  AdbOptions adb;  ///< --adb, --adb-serial, --adb-relay: the board through adb (docs/adb.md)
  bool no_vio = false;
  std::optional<bool> en_vio_output;
  std::string protocol_version = "2.0";
  int sysid = hil::kSimulatorSystemId;
  int compid = hil::kSimulatorComponentId;
  std::vector<std::string> fault_specs;  ///< --fault NAME[:ARGS][@T[+DUR]], repeatable
  std::string scenario_file;             ///< --scenario FILE.json
  std::string report_path;               ///< --report FILE.html: the recording drawn at the end (hitl report)
  std::vector<std::size_t> units_on;     ///< --rangefinder, ...: the sensor units turned on (of sensors::unit_infos())
};

/// "flight.html" -> "flight.tlog": where --report records when --record is not given.
std::string recording_for_report(const std::string& report_path) {
  const std::string ext = ".html";
  const bool html = report_path.size() > ext.size() && report_path.compare(report_path.size() - ext.size(), ext.size(), ext) == 0;
  return (html ? report_path.substr(0, report_path.size() - ext.size()) : report_path) + ".tlog";
}

/// --fault and --scenario into the session's faults (docs/faults.md); the error says which.
Status read_faults(const SimOptions& opt, std::vector<faults::FaultSpec>& out) {
  const faults::Suggest suggest = [](const std::string& name) { return closest(name, faults::fault_names()).value_or(""); };
  for (const auto& text : opt.fault_specs) {
    auto spec = faults::parse_fault(text, suggest);
    if (!spec) return spec.error().prefixed("--fault ");
    out.push_back(*spec);
  }
  if (!opt.scenario_file.empty()) {
    auto scenario = faults::load_scenario(opt.scenario_file, suggest);
    if (!scenario) return scenario.error().prefixed("--scenario: ");
    out.insert(out.end(), scenario->begin(), scenario->end());
  }
  if (auto limit = faults::check_active_limit(out); !limit) return limit.error().prefixed("--fault and --scenario: ");
  return Ok{};
}

/// --px4, --px4-param, --px4-speed, --px4-timeout into the session's PX4 launch.
Status read_px4_options(SimOptions& opt) {
  auto& cfg = opt.session;
  if (opt.px4_dir.empty()) {
    if (!opt.px4_params.empty() || opt.px4_speed)
      return Error::usage("--px4-param and --px4-speed need --px4 DIR (a PX4 that hitl starts)");
    return Ok{};
  }
  auto build = px4::find_px4_build(opt.px4_dir);  // found once, before anything opens; the error names the option
  if (!build) return build.error().prefixed("--px4: ");
  hil::Px4Options launch;
  launch.build = std::move(build.value());
  launch.connect_timeout_s = opt.px4_timeout_s;
  for (const auto& text : opt.px4_params) {
    auto p = px4::parse_px4_param(text);
    if (!p) return p.error().prefixed("--px4-param ");
    launch.params.push_back(*p);
  }
  if (opt.px4_speed) cfg.speed = *opt.px4_speed;
  if (!(cfg.speed > 0))
    return Error::usage("--speed 0 with --px4: PX4 runs in lockstep at a stated factor (PX4_SIM_SPEED_FACTOR); give "
                        "--px4-speed K (on a 2-core machine K <= 8 keeps PX4's estimator up)");
  cfg.px4 = std::move(launch);
  return Ok{};
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
  auto vehicle = opt.vehicle_file.empty() ? Expected<sensors::VehicleFile>(sensors::default_vehicle_file())
                                          : sensors::load_vehicle_file(opt.vehicle_file);
  if (!vehicle) {
    log_error(cmd, "--vehicle: " + vehicle.error().message);
    return exit_code(vehicle.error());
  }
  auto world = opt.world_file.empty() ? Expected<model::WorldConfig>(model::default_world_config())
                                      : model::load_world_config(opt.world_file);
  if (!world) {
    log_error(cmd, "--world: " + world.error().message);
    return exit_code(world.error());
  }
  std::optional<vehicle::Trajectory> for_f_key;  // with the dashboard the trajectory waits for the f key
  if (!opt.trajectory_file.empty()) {
    auto trajectory = vehicle::Trajectory::load(opt.trajectory_file);
    if (!trajectory) {
      log_error(cmd, "-t: " + trajectory.error().message);
      return exit_code(trajectory.error());
    }
    if (opt.tui) for_f_key = std::move(trajectory.value());
    else cfg.trajectory = std::move(trajectory.value());
  }
  if (auto faults_read = read_faults(opt, cfg.faults); !faults_read) {
    log_error(cmd, faults_read.error().message);
    return exit_code(faults_read.error());
  }
  cfg.vehicle = vehicle->vehicle;
  cfg.imu_profile = vehicle->imu_profile;
  cfg.sensor_units = vehicle->units;
  for (const std::size_t unit : opt.units_on) sensors::enable_unit(cfg.sensor_units, unit);
  cfg.world = *world;
  cfg.sysid = static_cast<uint8_t>(opt.sysid);
  cfg.compid = static_cast<uint8_t>(opt.compid);
  cfg.protocol = opt.protocol_version == "1.0" ? mavlink::Version::V1 : mavlink::Version::V2;
  if (opt.no_vio) cfg.vio = false;
  if (opt.en_vio_output) cfg.vio = *opt.en_vio_output;
  if (opt.px4_sitl_given) {
    auto sitl = hil::parse_px4_sitl(opt.px4_sitl.empty() ? "tcpin:" + std::to_string(hil::kPx4SitlTcpPort) : opt.px4_sitl,
                                    cfg.target_ip);
    if (!sitl) {
      log_error(cmd, "--px4-sitl " + sitl.error().message);
      return exit_code(sitl.error());
    }
    cfg.px4_sitl = *sitl;
  }
  if (auto px4 = read_px4_options(opt); !px4) {
    log_error(cmd, px4.error().message);
    return exit_code(px4.error());
  }
  if (cfg.local_port != 0 && cfg.local_port == cfg.clients_port && !cfg.px4 &&
      (cfg.bind_address == "0.0.0.0" || cfg.bind_address == cfg.clients_bind)) {
    // Both would bind the same UDP port: the second bind failed with "another process is bound
    // there", which sent the user looking for a process that was this one.
    return log_error(cmd, Error::usage("--clients " + std::to_string(cfg.clients_port) +
                                       " is also the --local-port of the HIL link; give them different ports"));
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
      return exit_code(opened.error());
    }
    tunnel = std::move(opened.value());
    log_info(global, "hitl sim: " + tunnel->describe());
    cfg.target_ip = "127.0.0.1";
    cfg.hil_port = tunnel->local_endpoint(adb::Channel::Hil).port();
    cfg.vio_ip = "127.0.0.1";
    cfg.vio_port = tunnel->local_endpoint(adb::Channel::Vio).port();
  }

  if (!opt.report_path.empty() && cfg.record_path.empty()) {
    cfg.record_path = recording_for_report(opt.report_path);
    log_info(global, "hitl sim: --report: recording to " + cfg.record_path);
  }
  auto session = hil::Session::create(cfg);
  if (!session) {
    log_error(cmd, session.error().message);
    return exit_code(session.error());
  }
  const auto& stop = stop_flag_on_signals();
  log_info(global, "hitl sim: " + (*session)->describe() + (opt.tui ? "" : " (Ctrl-C to stop)"));
  Expected<hil::Session::EndReason> end = Error::failed("not run");
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
    return exit_code(end.error());
  }
  // --report: drawn before the summary; its path printed last.
  std::optional<report::ReportResult> written;
  bool report_failed = false;
  if (!opt.report_path.empty()) {
    auto r = write_report_and_say(global, cmd, cfg.record_path, opt.report_path);
    if (r) written = *r;
    else report_failed = true;
  }
  if (global.json) {
    auto j = snapshot_json(snap, true);
    j["end"] = end_reason_name(*end);
    if (tunnel) j["adb"] = adb_tunnel_json(*tunnel);
    if (!opt.report_path.empty()) j["report"] = written ? report_json(*written) : nlohmann::json(nullptr);
    print_json_line(j);
  } else {
    print_summary(snap, end_reason_name(*end));
    if (tunnel) std::printf("%s\n", adb_tunnel_line(*tunnel).c_str());
    if (written) std::printf("%s\n", written->html_path.c_str());
  }
  std::fflush(stdout);
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
                      !snap.record_error.empty() || report_failed;
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
      "  hitl sim --px4 ~/px4/PX4-Autopilot # starts PX4 SITL, flies it, stops it (docs/sim.md)\n"
      "  hitl sim --px4-sitl               # PX4 SITL you start connects to TCP 4560 (tcpin:4560, lockstep)\n"
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
                                   "Serve PX4 SITL's simulator_mavlink instead of a board: tcpin:[HOST:]PORT (PX4 connects; "
                                   "bare: tcpin:4560) or udp:HOST:PORT (PX4's UDP simulator port); tcp:PORT and udp:PORT "
                                   "(at -i) still work")
                       ->expected(0, 1)->type_name("[tcpin:4560|udp:HOST:PORT]")->group(link);
  sub->add_option("--px4", opt->px4_dir,
                  "Start PX4 SITL and fly it (one command): DIR is a PX4 SITL build folder (bin/px4, etc/) or a PX4 "
                  "tree with build/px4_sitl_default (scripts/px4-sitl.sh); hitl picks a free instance, gives PX4 the "
                  "vehicle's parameters, routes clients to PX4's GCS port and stops PX4 at the end (docs/sim.md)")
      ->type_name("DIR")->group(link);
  sub->add_option("--px4-param", opt->px4_params,
                  "With --px4: set a PX4 parameter at its start, over hitl's (e.g. SYS_FAILURE_EN=1); repeatable")
      ->type_name("NAME=VALUE")->group(link);
  sub->add_option("--px4-speed", opt->px4_speed,
                  "With --px4: lockstep at K times real time in both hitl and PX4 (--speed K and PX4_SIM_SPEED_FACTOR=K)")
      ->check(positive_number())->type_name("K")->group(link);
  sub->add_option("--px4-timeout", opt->px4_timeout_s, "With --px4: end the session when PX4 has not connected within S seconds")
      ->capture_default_str()->check(positive_number())->type_name("S")->group(link);
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
  sub->add_option("--spin-us", c.spin_us,
                  "Spin on the clock for the last US microseconds before each tick instead of sleeping (less "
                  "jitter at the board, that much more CPU); 0..2000")
      ->capture_default_str()->check(number_in(0, 2000))->type_name("US")->group(timing);

  const char* model = "Model";
  sub->add_option("--vehicle", opt->vehicle_file, "Vehicle JSON over the compiled-in x500 (docs/engine.md)")
      ->check(CLI::ExistingFile)->group(model);
  sub->add_option("--world", opt->world_file, "World JSON: home, magnetic field, wind (docs/engine.md)")
      ->check(CLI::ExistingFile)->group(model);
  // "-1" is refused by the check every unsigned option gets (cli/number_check.h), not wrapped to 2^64 - 1.
  sub->add_option("--seed", c.seed, "Noise and gust seed (runs repeat)")
      ->capture_default_str()
      ->group(model);
  sub->add_option("--board-timing", c.board_timing,
                  "Delay the sensors as the board's data path does before PX4 reads them: voxl2 (the HIL split's "
                  "4 ms IMU and 10 ms mag/baro publishing, dsp_hitl's 4 ms poll: 0-8 ms IMU, 0-14 ms mag/baro; "
                  "docs/sim.md), or none")
      ->check(CLI::IsMember(std::vector<std::string>(sensors::kBoardTimingModels.begin(), sensors::kBoardTimingModels.end())))
      ->capture_default_str()
      ->group(model);
  sub->add_flag("--no-noise", [opt](int64_t) { opt->session.noise = false; },
                "Noise-free sensors (tests only: PX4 marks repeating values stale and refuses to arm)")
      ->group(model);
  // The sensor units (engine/sensors/units.h), each turned on by its own flag: --rangefinder, ...
  const auto units = sensors::unit_infos();
  for (std::size_t i = 0; i < units.size(); ++i)
    sub->add_flag("--" + units[i].name, [opt, i](int64_t) { opt->units_on.push_back(i); }, units[i].summary)->group(model);

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

  const char* faults_group = "Faults (docs/faults.md)";
  std::string names;
  for (const auto& f : faults::fault_catalogue()) names += std::string(names.empty() ? "" : ", ") + f.name;
  sub->add_option("--fault", opt->fault_specs,
                  "Inject a fault at simulated time T for DUR seconds (without @T: from the start; without +DUR: to the "
                  "end), e.g. gps-loss@20+10, motor:2,0.6@15; repeatable. Faults: " + names +
                      " (their arguments and units: docs/faults.md)")
      ->type_name(value_type::kFaultSpec)->group(faults_group);
  sub->add_option("--scenario", opt->scenario_file,
                  "Faults from a JSON file: {\"events\": [{\"at_s\": 20, \"fault\": \"gps-loss\", \"duration_s\": 10}, ...]}")
      ->type_name("FILE.json")->group(faults_group);

  sub->add_flag("--tui", opt->tui,
                "The live dashboard (docs/tui.md): data paths, dsp_hitl, EKF, vehicle, messages, link; keys a arm, d disarm, "
                "t takeoff, l land, p pause, r reset, f fly the -t file (waits for the key), s shell, x start or clear a fault (docs/faults.md), ? help, q quit. "
                "Without a terminal: the status lines")
      ->group("Dashboard");

  const char* route = "Clients and recording";
  sub->add_option("--clients", c.clients_port, "UDP port on 127.0.0.1 for local MAVLink clients (other hitl commands); 0: none")
      ->capture_default_str()->check(number_in(0, 65535))->group(route);
  sub->add_option("--gcs", c.gcs,
                  "Also route the board's telemetry to a ground station at udp:HOST:PORT (or HOST:PORT; QGroundControl: "
                  "udp:127.0.0.1:14550)")
      ->type_name("udp:HOST:PORT")->group(route);
  sub->add_option("--truth-rate", c.truth_rate_hz,
                  "Ground truth to clients as ODOMETRY (sysid " + std::to_string(hil::kSimulatorSystemId) +
                      ", estimator MOCAP), Hz; 0: none")
      ->capture_default_str()->check(non_negative_number())->group(route);
  sub->add_option("--record", c.record_path, "Save everything sent and received to a .tlog")->type_name("FILE.tlog")->group(route);
  sub->add_option("--report", opt->report_path,
                  "At the end, draw the recording as an HTML page (hitl report; docs/report.md); without --record, "
                  "records to FILE with .tlog")
      ->type_name("FILE.html")->group(route);
  // Through adb the board's ports are the relay's; an address for them would be ignored.
  for (const char* adb_name : {"--adb", "--adb-serial"})
    for (const char* other : {"--target-ip", "--hil-port", "--vio-ip", "--vio-port", "--px4-sitl", "--px4"})
      sub->get_option(adb_name)->excludes(sub->get_option(other));
  // --px4 names the flight stack and its links: a board's or a user-started PX4's are not asked for.
  for (const char* other : {"--px4-sitl", "--target-ip", "--hil-port", "--local-port"})
    sub->get_option("--px4")->excludes(sub->get_option(other));
  sub->callback([&options, &state, opt, px4_sitl]() {
    opt->px4_sitl_given = px4_sitl->count() > 0;  // also when given bare: `--px4-sitl` means tcp:4560
    state.exit_code = run_sim(options, *opt);
  });
}

}  // namespace hitl::cli
