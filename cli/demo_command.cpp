// hitl demo: the first thing a newcomer runs. An emulated board (in this process, on free
// loopback ports) and the simulator in lockstep fly docs/examples/square.json (takeoff, a 5 m
// square, land), then a short report: tracking error, rates achieved, the board's estimate
// against the simulator's truth. No board, no network, no configuration. Ctrl-C stops it all.
// --tui: the sim dashboard (docs/tui.md) on the flight, in real time unless --speed says otherwise.
// --campaign: instead, the small campaign of docs/examples/campaigns/small.toml (4 hovers, with and
// without a GPS loss) flown as `hitl campaign run` flies it, its page (index.html) last.
#include <unistd.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

#include "cli/campaign_command.h"
#include "cli/commands.h"
#include "cli/number_check.h"
#include "cli/report_output.h"
#include "cli/session_dashboard.h"
#include "emulator/board.h"
#include "engine/hil/session.h"
#include "engine/model/x500_defaults.h"
#include "engine/net/udp_endpoint.h"
#include "engine/vehicle/telemetry_feed.h"
#include "engine/vehicle/trajectory.h"
#include "engine/px4/px4_build.h"
#include "tui/terminal.h"

namespace hitl::cli {

extern const char* const kSquareTrajectory;  // docs/examples/square.json, compiled in
extern const char* const kSmallCampaign;     // docs/examples/campaigns/small.toml, compiled in
extern const char* const kHoverTrajectory;   // docs/examples/hover.json (small.toml's trajectory), compiled in

namespace {

struct DemoOptions {
  std::string trajectory_file;  ///< empty: the compiled-in square
  double speed = 0;             ///< 0: as fast as lockstep allows
  bool speed_given = false;     ///< --speed on the command line (--tui otherwise flies in real time)
  bool tui = false;             ///< --tui: the sim dashboard on the demo
  vehicle::StickMode mode = vehicle::StickMode::Velocity;
  std::string record_path;      ///< --record (empty: demo.tlog in a new directory under $TMPDIR)
  std::string report_path;      ///< --report (empty: demo.html beside the recording)
  bool no_report = false;       ///< --no-report
  std::string px4_dir;          ///< --px4 DIR: real PX4 SITL, started by hitl, instead of the emulated board
  bool campaign = false;        ///< --campaign: the small campaign and its page instead of the one flight
};

/// --px4 without --speed: lockstep at this factor (a 2-core machine keeps PX4's estimator up to ~8).
constexpr double kPx4DemoSpeed = 5;

/// A new directory for the demo's recording and report: $TMPDIR/hitl-demo-XXXXXX.
Expected<std::string> demo_directory() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "hitl-demo-XXXXXX").string();
  if (::mkdtemp(tmpl.data()) == nullptr)
    return Error::unavailable("cannot make a directory for the recording under " + std::filesystem::temp_directory_path().string() +
                              ": " + std::strerror(errno) + " (--record FILE.tlog, or --no-report)");
  return tmpl;
}

/// The demo folders kept under $TMPDIR: each demo removes this user's older ones beyond these.
constexpr std::size_t kDemoFoldersKept = 5;

/// Removes this user's hitl-demo-XXXXXX folders under $TMPDIR beyond the newest kDemoFoldersKept
/// (by modification time; `current` is always kept); how many went.
std::size_t remove_old_demo_folders(const std::string& current) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> folders;
  const std::string prefix = "hitl-demo-";
  for (fs::directory_iterator it(fs::temp_directory_path(ec), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() != prefix.size() + 6 || name.rfind(prefix, 0) != 0 || it->path() == fs::path(current)) continue;
    struct stat st{};
    if (::lstat(it->path().c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::getuid()) continue;
    folders.emplace_back(fs::last_write_time(it->path(), ec), it->path());
  }
  if (folders.size() < kDemoFoldersKept) return 0;
  std::sort(folders.begin(), folders.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::size_t removed = 0;
  for (std::size_t i = kDemoFoldersKept - 1; i < folders.size(); ++i)
    if (fs::remove_all(folders[i].second, ec) > 0 && !ec) ++removed;
  return removed;
}

/// A loopback UDP port nobody uses right now (the OS picks it): probed and let go, so another
/// process could take it before the session binds it; only the clients port's fallback uses it.
Expected<uint16_t> free_port() {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.name = "a free loopback port";
  auto ep = net::UdpEndpoint::open(c);
  if (!ep) return ep.error();
  return ep->local_address().port();
}

/// The emulated board's events: on stderr, or in the dashboard's messages panel while it is shown.
class BoardEvents : public target::Board::Observer {
 public:
  explicit BoardEvents(const GlobalOptions& g) : g_(g) {}
  void on_event(const target::BoardEvent& e) override {
    if (e.severity == Severity::Info && g_.verbosity == 0) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (dashboard_ != nullptr)
      dashboard_->note(e.severity, "board: " + e.text);
    else
      std::cerr << "hitl demo: board: " << e.text << '\n';
  }
  void attach(tui::SimDashboard* dashboard) {
    std::lock_guard<std::mutex> lock(mutex_);
    dashboard_ = dashboard;
  }

 private:
  const GlobalOptions& g_;
  std::mutex mutex_;
  tui::SimDashboard* dashboard_ = nullptr;
};

class SessionEvents : public hil::Session::Observer {
 public:
  explicit SessionEvents(const GlobalOptions& g) : g_(g) {}
  void on_event(const hil::SessionEvent& e) override {
    if (e.severity != hil::Severity::Info || !g_.quiet) std::cerr << "hitl demo: " << e.text << '\n';
  }
  void on_status(const hil::SessionSnapshot& s) override {
    if (g_.json) {
      print_json_line({{"type", "status"}, {"sim_time_s", s.sim_time_s}, {"trajectory", s.trajectory_state},
                       {"altitude_m", s.altitude_m}, {"armed", s.armed}, {"send_errors", s.send_errors}});
      return;
    }
    if (g_.quiet) return;
    char line[160];
    std::snprintf(line, sizeof line, "hitl demo: t %5.1f s  %-10s alt %5.2f m  %s", s.sim_time_s, s.trajectory_state.c_str(),
                  s.altitude_m, s.armed ? "armed" : "disarmed");
    std::cerr << line << '\n';
  }

 private:
  const GlobalOptions& g_;
};

/// A measured figure, or "n/a" when there was nothing to measure.
std::string figure(bool measured, const char* format, double value) {
  if (!measured) return "n/a";
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

/// The same for JSON: null when not measured.
nlohmann::json measured_or_null(bool measured, double value) { return measured ? nlohmann::json(value) : nlohmann::json(nullptr); }

double per_sim_second(const std::map<std::string, hil::StreamCount>& counts, const char* name, double sim_s) {
  const auto it = counts.find(name);
  return it == counts.end() || sim_s <= 0 ? 0.0 : static_cast<double>(it->second.count) / sim_s;
}

/// `text` into `path`; an Error naming it when it cannot be written.
Status write_file(const std::filesystem::path& path, const char* text) {
  std::ofstream out(path, std::ios::trunc);
  out << text;
  if (!out) return Error::unavailable("cannot write " + path.string() + ": " + std::strerror(errno));
  return Ok{};
}

/// hitl demo --campaign: small.toml and its hover written into a new demo folder (as they lie in
/// docs/examples, so the flights' ids are the docs' ones), flown -j cores into DIR/results with a
/// history of its own (DIR/history.sqlite), the page's path last.
int run_demo_campaign(const GlobalOptions& g) {
  namespace fs = std::filesystem;
  auto dir = demo_directory();
  if (!dir) return log_error("demo", dir.error());
  if (const std::size_t removed = remove_old_demo_folders(*dir); removed > 0)
    log_info(g, "hitl demo: removed " + std::to_string(removed) + " older demo folder" + (removed == 1 ? "" : "s") + " under " +
                    fs::temp_directory_path().string() + " (the newest " + std::to_string(kDemoFoldersKept) + " are kept)");
  const fs::path root(*dir);
  std::error_code ec;
  fs::create_directories(root / "campaigns", ec);
  if (ec) return log_error("demo", Error::unavailable("cannot make " + (root / "campaigns").string() + ": " + ec.message()));
  const fs::path file = root / "campaigns" / "small.toml";
  for (auto [path, text] : {std::pair{root / "hover.json", kHoverTrajectory}, std::pair{file, kSmallCampaign}})
    if (auto ok = write_file(path, text); !ok) return log_error("demo", ok.error());
  CampaignFileRun run;
  run.file = file.string();
  run.jobs = std::max(1u, std::thread::hardware_concurrency());
  run.out_dir = (root / "results").string();
  run.history = (root / "history.sqlite").string();
  run.label = "demo";
  const std::string page = (root / "results" / "index.html").string();
  log_info(g, "hitl demo: a small campaign (docs/examples/campaigns/small.toml: a hover with and without a GPS loss, 2 seeds: "
              "4 flights) against the emulated board, " + std::to_string(run.jobs) + " at a time, into " + run.out_dir +
              " (Ctrl-C stops it)");
  if (g.json)
    print_json_line({{"type", "status"}, {"event", "campaign"}, {"campaign", run.file}, {"out", run.out_dir}, {"page", page}});
  const int code = run_campaign_file(g, run);
  if (!g.json && fs::exists(page, ec)) {
    std::cout << "Next: docs/campaigns.md (a campaign file of your own, JUnit for CI, the history). Fly it again into the "
                 "same history, and its page draws the trend of each criterion:\n  hitl campaign run "
              << run.file << " --out " << (root / "again").string() << " --history " << run.history << "\nThe campaign's page:\n"
              << page << '\n' << std::flush;
  }
  return code;
}

int run_demo(const GlobalOptions& g, DemoOptions o) {
  if (o.campaign) return run_demo_campaign(g);
  if (o.tui) {
    if (auto usable = tui::terminal_usable(); !usable) {
      std::cerr << "hitl demo: --tui: " << usable.error().message << "; showing the status lines instead\n";
      o.tui = false;
    } else if (!o.speed_given) {
      o.speed = 1;  // to be watched: real time
    }
  }
  auto trajectory = o.trajectory_file.empty() ? vehicle::Trajectory::parse(kSquareTrajectory, "docs/examples/square.json")
                                              : vehicle::Trajectory::load(o.trajectory_file);
  if (!trajectory) {
    log_error("demo", trajectory.error().message);
    return exit_code(trajectory.error());
  }
  // Loopback ports the OS picks for the board's instances and the simulator (below), so a demo never
  // collides with a real session; the clients port is the usual one when free, so `hitl arm` etc. work.
  target::BoardConfig board_config;
  board_config.bind_address = "127.0.0.1";
  board_config.lockstep = true;
  hil::SessionConfig session;
  const bool px4 = !o.px4_dir.empty();
  if (px4) {  // real PX4, which hitl starts on an instance of its own (engine/hil/px4_launch.h)
    auto build = px4::find_px4_build(o.px4_dir);
    if (!build) return log_error("demo", build.error().prefixed("--px4: "));
    session.px4 = hil::Px4Options{};
    session.px4->build = std::move(build.value());
    session.vio = false;
    if (!o.speed_given && !o.tui) o.speed = kPx4DemoSpeed;
    if (!(o.speed > 0)) {
      return log_error("demo", Error::usage("--speed 0 with --px4: PX4 runs in lockstep at a stated factor; give --speed K "
                                            "(K <= 8 on 2 cores)"));
    }
  }
  // The board binds ports the OS picks and keeps them (no port is probed and let go); the session's
  // own port is the OS's too, and the board answers whoever spoke to it.
  board_config.os_picks_ports = true;
  std::unique_ptr<target::Board> board;
  if (!px4) {
    auto created = target::Board::create(board_config);
    if (!created) {
      log_error("demo", created.error().message);
      return exit_code(created.error());
    }
    board = std::move(created.value());
    const auto bound = board->ports();
    session.hil_port = bound.hil_port;
    session.vio_port = bound.vio_port;
    session.local_port = 0;
  }
  session.target_ip = "127.0.0.1";
  session.bind_address = "127.0.0.1";
  session.lockstep = true;
  session.speed = o.speed;
  session.vehicle = model::x500_vehicle_config();
  session.world = model::default_world_config();
  session.trajectory = std::move(trajectory.value());
  session.trajectory_mode = o.mode;
  if (!o.no_report || !o.record_path.empty()) {
    if (o.record_path.empty()) {
      auto dir = demo_directory();
      if (!dir) {
        log_error("demo", dir.error().message);
        return exit_code(dir.error());
      }
      o.record_path = *dir + "/demo.tlog";
      if (const std::size_t removed = remove_old_demo_folders(*dir); removed > 0)
        log_info(g, "hitl demo: removed " + std::to_string(removed) + " older demo folder" + (removed == 1 ? "" : "s") + " under " +
                        std::filesystem::temp_directory_path().string() + " (the newest " + std::to_string(kDemoFoldersKept) +
                        " are kept; --record FILE.tlog keeps yours)");
    }
    if (o.report_path.empty()) o.report_path = default_report_path(o.record_path);
    session.record_path = o.record_path;
  }
  {
    net::UdpEndpoint::Config c;
    c.bind_address = session.clients_bind;
    c.bind_port = session.clients_port;
    if (!net::UdpEndpoint::open(c)) {  // a session or bridge already there: keep out of its way
      auto p = free_port();
      if (!p) {
        log_error("demo", p.error().message);
        return exit_code(p.error());
      }
      session.clients_port = *p;
    }
  }

  auto sim = hil::Session::create(session);
  if (!sim) {
    log_error("demo", sim.error().message);
    return exit_code(sim.error());
  }
  const std::string flown = o.trajectory_file.empty() ? std::string("docs/examples/square.json") : o.trajectory_file;
  if (px4)
    log_info(g, "hitl demo: real PX4 SITL, started by hitl, and the Simbody x500 in lockstep at " + figure(true, "%gx", o.speed) +
                    ", flying " + flown + "; " + (*sim)->describe() + " (Ctrl-C stops everything)");
  else
    log_info(g, "hitl demo: an emulated VOXL2 board (not PX4) and the Simbody x500 in lockstep, flying " + flown +
                    "; clients on 127.0.0.1:" + std::to_string(session.clients_port) + " (Ctrl-C stops everything)");

  const auto& stop = stop_flag_on_signals();
  std::atomic<bool> stop_board{false};
  BoardEvents board_events(g);
  std::thread board_thread;
  if (board) board_thread = std::thread([&] { (void)board->run(stop_board, board_events); });

  // The estimate against the truth, as any client of the session sees it.
  vehicle::LinkOptions link;
  link.connect = "udp:127.0.0.1:" + std::to_string(session.clients_port);
  link.local_port = 0;
  vehicle::TelemetryFeed feed(link, vehicle::dashboard_streams(), [](mavlink::MavSeverity, const std::string&) {},
                              hil::kSimulatorSystemId);

  Expected<hil::Session::EndReason> end = Error::failed("not run");
  if (o.tui) {
    tui::SimDashboardConfig dc;
    dc.title = "hitl demo";
    dc.no_trajectory_hint = "the demo flies its trajectory by itself";
    end = run_session_with_dashboard(g, "demo", **sim, session, dc,
                                     [&board_events](tui::SimDashboard* d) { board_events.attach(d); });
  } else {
    SessionEvents events(g);
    end = (*sim)->run(stop, events);
  }
  const auto estimate = feed.snapshot();
  feed.stop();
  stop_board = true;
  if (board_thread.joinable()) board_thread.join();
  if (!end) {
    log_error("demo", end.error().message);
    return exit_code(end.error());
  }
  const auto s = (*sim)->snapshot();
  const auto b = board ? board->snapshot() : target::BoardSnapshot{};
  const bool done = *end == hil::Session::EndReason::TrajectoryDone;
  const double sim_s = s.sim_time_s;
  const auto& err = estimate.estimate_error;
  // The report of the recording: written before the summary, its path printed last.
  std::optional<report::ReportResult> written;
  bool report_failed = false;
  if (!o.no_report) {
    if (!s.record_error.empty()) log_error("demo", "--record: " + s.record_error + "; the recording is incomplete");
    auto r = write_report_and_say(g, "demo", o.record_path, o.report_path);
    if (r) written = *r;
    else report_failed = true;
  }
  if (g.json) {
    print_json_line({{"type", "summary"},
                     {"ok", done},
                     {"end", *end == hil::Session::EndReason::Stopped ? "stopped" : done ? "trajectory_done" : "trajectory_failed"},
                     {"trajectory", {{"state", s.trajectory_state}, {"failure", s.trajectory_failure},
                                     {"rms_m", measured_or_null(s.trajectory_samples > 0, s.trajectory_rms_m)},
                                     {"max_m", measured_or_null(s.trajectory_samples > 0, s.trajectory_max_m)},
                                     {"samples", s.trajectory_samples}}},
                     {"sim_time_s", sim_s},
                     {"wall_time_s", s.wall_time_s},
                     {"rates_hz", {{"HIL_SENSOR", measured_or_null(sim_s > 0, per_sim_second(s.sent, "HIL_SENSOR", sim_s))},
                                   {"HIL_GPS", measured_or_null(sim_s > 0, per_sim_second(s.sent, "HIL_GPS", sim_s))},
                                   {"ODOMETRY", measured_or_null(sim_s > 0, per_sim_second(s.sent, "ODOMETRY", sim_s))},
                                   {"HIL_ACTUATOR_CONTROLS",
                                    measured_or_null(sim_s > 0, per_sim_second(s.received, "HIL_ACTUATOR_CONTROLS", sim_s))}}},
                     {"estimate_error", {{"horizontal_rms_m", measured_or_null(err.position_samples > 0, err.horizontal_rms_m)},
                                         {"attitude_rms_deg", measured_or_null(err.attitude_samples > 0, err.attitude_rms_deg)},
                                         {"position_samples", err.position_samples},
                                         {"attitude_samples", err.attitude_samples}}},
                     {"board", px4 ? nlohmann::json(nullptr)
                                   : nlohmann::json{{"hil_sensor_received", b.hil_sensor_received},
                                                    {"hil_gps_received", b.hil_gps_received},
                                                    {"odometry_received", b.odometry_received},
                                                    {"actuators_sent", b.actuators_sent}, {"malformed", b.malformed}}},
                     {"px4", !px4 ? nlohmann::json(nullptr)
                                  : nlohmann::json{{"instance", s.px4.instance}, {"version", s.px4.version},
                                                   {"work_dir", s.px4.work_dir}, {"console", s.px4.console}}},
                     {"recording", o.record_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.record_path)},
                     {"report", written ? report_json(*written) : nlohmann::json(nullptr)}});
  } else {
    // A demo stopped before it flew has measured nothing: n/a, not zeros.
    const bool tracked = s.trajectory_samples > 0, timed = sim_s > 0;
    auto hz = [&](const std::map<std::string, hil::StreamCount>& m, const char* name) {
      return figure(timed, "%.0f Hz", per_sim_second(m, name, sim_s));
    };
    const std::string flight_stack =
        px4 ? "PX4 " + s.px4.version + " instance " + std::to_string(s.px4.instance) + " (its console " + s.px4.console +
                  ", its ULogs in " + s.px4.work_dir + "/log)"
            : "board: " + std::to_string(b.hil_sensor_received) + " HIL_SENSOR, " + std::to_string(b.malformed) + " malformed";
    char text[2048];
    std::snprintf(text, sizeof text,
                  "\n%s: %s%s\n"
                  "  tracking error against truth   RMS %s, max %s (%llu samples)\n"
                  "  rates (per simulated second)    HIL_SENSOR %s, HIL_GPS %s, ODOMETRY %s, HIL_ACTUATOR_CONTROLS back %s\n"
                  "  estimate vs truth               horizontal RMS %s, attitude RMS %s\n"
                  "  simulated %.1f s in %.1f s of wall time; %s\n",
                  done ? "demo flown" : "demo did not finish", s.trajectory_state.c_str(),
                  s.trajectory_failure.empty() ? "" : (" (" + s.trajectory_failure + ")").c_str(),
                  figure(tracked, "%.2f m", s.trajectory_rms_m).c_str(), figure(tracked, "%.2f m", s.trajectory_max_m).c_str(),
                  static_cast<unsigned long long>(s.trajectory_samples), hz(s.sent, "HIL_SENSOR").c_str(),
                  hz(s.sent, "HIL_GPS").c_str(), hz(s.sent, "ODOMETRY").c_str(), hz(s.received, "HIL_ACTUATOR_CONTROLS").c_str(),
                  figure(err.position_samples > 0, "%.2f m", err.horizontal_rms_m).c_str(),
                  figure(err.attitude_samples > 0, "%.2f deg", err.attitude_rms_deg).c_str(), sim_s, s.wall_time_s,
                  flight_stack.c_str());
    std::cout << text << "Next: README.md (a real board, PX4 SITL, the other commands).\n";
    if (!o.record_path.empty()) std::cout << "Recorded in " << o.record_path << (written ? "; the flight drawn:" : "") << '\n';
    if (written) std::cout << written->html_path << '\n';
  }
  std::cout << std::flush;
  return done && !report_failed ? kExitOk : kExitFailed;
}

}  // namespace

void add_demo_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<DemoOptions>();
  auto* sub = app.add_subcommand(
      "demo", "Fly the x500 on an emulated board with no hardware: take off, fly a 5 m square, land; then a report");
  sub->add_option("-t,--trajectory", o->trajectory_file, "Another trajectory file (default: docs/examples/square.json, built in)")
      ->check(CLI::ExistingFile)->type_name("FILE.json");
  sub->add_option("--speed", o->speed, "Real-time factor; 0: as fast as lockstep allows")->capture_default_str()
      ->check(non_negative_number());
  sub->add_option("--trajectory-mode", o->mode, "velocity (Position mode) or attitude (Stabilized)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, vehicle::StickMode>{{"velocity", vehicle::StickMode::Velocity},
                                                                                  {"attitude", vehicle::StickMode::Attitude}}))
      ->default_str("velocity");
  auto* speed = sub->get_option("--speed");
  sub->add_option("--record", o->record_path, "Save everything sent and received to this .tlog (default: demo.tlog in a new "
                                              "directory under $TMPDIR)")->type_name("FILE.tlog");
  sub->add_option("--report", o->report_path, "Write the flight's report (hitl report) here (default: the recording's name "
                                              "with .html); its path is the last line printed")->type_name("FILE.html");
  sub->add_flag("--no-report", o->no_report, "No report (and no recording unless --record)");
  sub->add_option("--px4", o->px4_dir,
                  "Fly it with real PX4 SITL instead of the emulated board: DIR is a PX4 SITL build folder or a PX4 tree "
                  "with build/px4_sitl_default (scripts/px4-sitl.sh); hitl starts and stops PX4 (docs/sim.md); at 5x "
                  "real time unless --speed is given")
      ->type_name("DIR");
  sub->add_flag("--tui", o->tui,
                "Watch it on the sim dashboard (docs/tui.md), in real time unless --speed is given; the report "
                "follows when the flight ends or on q. Without a terminal: the status lines");
  auto* campaign = sub->add_flag("--campaign",
                                 o->campaign,
                                 "Instead of the one flight: a small campaign (docs/examples/campaigns/small.toml, built in: 4 "
                                 "hovers, with and without a GPS loss) flown as hitl campaign run does, into a new folder "
                                 "under $TMPDIR; its page (index.html) is the last line printed");
  for (const char* other : {"--trajectory", "--speed", "--trajectory-mode", "--record", "--report", "--no-report", "--px4", "--tui"})
    campaign->excludes(sub->get_option(other));
  sub->footer("Exit: 0 when the trajectory was flown and the vehicle landed and disarmed (--campaign: every flight passed), 1 "
              "otherwise.");
  sub->callback([&options, &state, o, speed]() {
    o->speed_given = speed->count() > 0;
    state.exit_code = run_demo(options, *o);
  });
}

}  // namespace hitl::cli
