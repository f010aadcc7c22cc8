// hitl board install | start | stop | status | restore: the VOXL2's side of HITL over adb
// (engine/board, docs/board.md). Each subcommand surveys the board (read-only), makes its plan and
// either prints it (--dry-run) or runs it, saying each step before it runs; a failure names the
// step, the board's output, what is already changed and how to undo it.
#include <iostream>

#include "base/common/shell_quote.h"
#include "cli/adb_options.h"
#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "cli/version.h"
#include "engine/board/board_facts.h"
#include "engine/board/board_plan.h"
#include "engine/board/board_shell.h"
#include "engine/board/board_status.h"
#include "engine/board/plan_runner.h"
#include "engine/board/px4_link.h"
#include "engine/net/adb_client.h"
#include "engine/net/socket_address.h"

namespace hitl::cli {
namespace {

struct BoardOptions {
  bool adb = false;                 ///< --adb: over USB (the default)
  bool network = false;             ///< -i given without --adb/--adb-serial: adb over the network (adb connect IP:5555)
  bool link_given = false;          ///< -i or --connect given: PX4's MAVLink there; else through the adb tunnel
  std::string px4_unreachable;      ///< status: why there is no way to PX4 (the tunnel did not open)
  std::string adb_serial;           ///< --adb-serial S
  bool dry_run = false;             ///< --dry-run
  std::vector<std::string> files;   ///< install: .deb files
  std::string packages_dir = ".";   ///< install --packages DIR
  bool reset_params = false;        ///< start --reset-params
  double wait_s = 60.0;             ///< start --wait
  bool keep = false;                ///< restore --keep
  std::string params = "keep";      ///< restore --params keep|remove
  vehicle::LinkOptions link;        ///< start, status: PX4's GCS instance
};

nlohmann::json action_json(const board::BoardAction& a) { return a.text(); }

nlohmann::json plan_json(const board::BoardPlan& plan) {
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& s : plan.steps) {
    nlohmann::json actions = nlohmann::json::array();
    for (const auto& a : s.actions) actions.push_back(action_json(a));
    steps.push_back({{"name", s.name}, {"details", s.details}, {"actions", actions}, {"undo", s.undo}, {"changes_board", s.changes_board}});
  }
  return steps;
}

/// Ends a run: the summary with --json, the exit code.
struct Reporter {
  const GlobalOptions& g;
  std::string action;
  void summary(nlohmann::json body) const {
    if (!g.json) return;
    body["type"] = "summary";
    body["command"] = "board";
    body["action"] = action;
    print_json_line(body);
  }
  int error(const Error& e) const {
    log_error("board " + action, e.message);
    summary({{"ok", false}, {"error", e.message}});
    return exit_code(e);
  }
};

void print_lines(const std::vector<std::string>& lines) {
  for (const auto& l : lines) std::cout << l << '\n';
  std::cout << std::flush;
}

int run_plan_command(const GlobalOptions& g, const BoardOptions& o, const Reporter& r, board::BoardShell& shell,
                     const board::BoardPlan& plan) {
  if (o.dry_run) {
    if (!g.json) {
      print_lines(board::plan_lines(plan));
      std::cout << "dry run: nothing was changed on the board\n";
    }
    r.summary({{"ok", true}, {"dry_run", true}, {"board", shell.describe()}, {"notes", plan.notes}, {"steps", plan.steps.size()},
               {"plan", plan_json(plan)}, {"undo_command", plan.undo_command}});
    return kExitOk;
  }
  if (!g.json)
    for (const auto& n : plan.notes) std::cout << "note: " << n << '\n';
  board::HostActions host{[&]() { return board::wait_for_px4(o.link, o.wait_s); }, [&]() { return board::push_hitl_params(o.link); }};
  board::RunCallbacks callbacks{[&](std::size_t i) {
                                  if (g.json) {
                                    print_json_line({{"type", "status"}, {"command", "board"}, {"action", r.action}, {"step", i + 1},
                                                     {"of", plan.steps.size()}, {"name", plan.steps[i].name}});
                                  } else {
                                    print_lines(board::step_lines(plan, i));
                                  }
                                },
                                [&](const std::string& line) {
                                  if (g.json) print_json_line({{"type", "status"}, {"command", "board"}, {"action", r.action}, {"said", line}});
                                  else std::cout << "      -> " << line << std::endl;
                                }};
  const auto report = board::run_plan(plan, shell, host, callbacks);
  nlohmann::json body{{"ok", report.ok},       {"dry_run", false},           {"board", shell.describe()},
                      {"steps", plan.steps.size()}, {"steps_done", report.steps_done}, {"changed", report.changed},
                      {"params_set", report.params_set}, {"params_restart", report.params_restart}};
  if (report.ok) {
    if (!g.json)
      std::cout << "done: " << plan.steps.size() << " steps" << (plan.undo_command.empty() ? "" : "; undo with: " + plan.undo_command) << '\n';
    r.summary(body);
    return kExitOk;
  }
  const std::size_t i = *report.failed_step;
  std::string message = "step " + std::to_string(i + 1) + "/" + std::to_string(plan.steps.size()) + " \"" + plan.steps[i].name +
                        "\" failed: " + report.failed_action + ": " + report.error;
  log_error("board " + r.action, message);
  if (!g.quiet) {
    if (!report.board_output.empty()) {
      std::cerr << "the board said:\n";
      std::istringstream in(report.board_output);
      for (std::string line; std::getline(in, line);) std::cerr << "  " << line << '\n';
    }
    if (!plan.after_failure.empty()) std::cerr << plan.after_failure << '\n';
    if (report.changed.empty()) {
      std::cerr << "nothing was changed on the board\n";
    } else {
      std::cerr << "already changed on the board:\n";
      for (const auto& c : report.changed) std::cerr << "  - " << c << (c == plan.steps[i].name ? " (may be partly done)" : "") << '\n';
      if (!plan.undo_command.empty() || !report.undo.empty()) std::cerr << "to undo: " << (plan.undo_command.empty() ? "by hand" : plan.undo_command) << '\n';
      if (!report.undo.empty()) {
        std::cerr << (plan.undo_command.empty() ? "" : "  or by hand, in this order:\n");
        for (const auto& u : report.undo) std::cerr << "    adb shell " << shell_quoted(u) << '\n';
      }
    }
  }
  body["error"] = message;
  body["failed_step"] = {{"index", i + 1}, {"name", plan.steps[i].name}, {"action", report.failed_action}, {"error", report.error},
                         {"board_output", report.board_output}};
  body["undo"] = report.undo;
  body["undo_command"] = plan.undo_command;
  body["after_failure"] = plan.after_failure;
  r.summary(body);
  return kExitFailed;
}

nlohmann::json keys_json(const board::ConfigKeys& c) {
  if (!c.present) return nullptr;
  if (!c.error.empty()) return {{"error", c.error}};
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [k, v] : c.keys) j[k] = v == "absent" ? nlohmann::json(nullptr) : nlohmann::json::parse(v);
  return j;
}

std::string keys_text(const board::ConfigKeys& c) {
  if (!c.present) return "absent";
  if (!c.error.empty()) return c.error;
  std::string t;
  for (const auto& [k, v] : c.keys) t += (t.empty() ? "" : ", ") + k + " " + v;
  return t;
}

int run_status(const GlobalOptions& g, const BoardOptions& o, const Reporter& r, board::BoardShell& shell, const board::BoardSurvey& survey) {
  board::Px4Status px4;
  if (o.px4_unreachable.empty()) px4 = board::read_px4_status(o.link);
  else px4.link_error = o.px4_unreachable;
  const auto s = board::make_board_status(survey, kVersion, px4);
  if (g.json) {
    nlohmann::json packages = nlohmann::json::array(), services = nlohmann::json::object(), wrong = nlohmann::json::array(),
                   absent = nlohmann::json::array();
    for (const auto& p : s.packages)
      packages.push_back({{"name", p.name}, {"installed", p.installed.empty() ? nlohmann::json(nullptr) : nlohmann::json(p.installed)},
                          {"this_build", p.this_build}, {"current", p.current()}});
    for (const auto& sv : s.services) services[sv.name] = {{"enabled", sv.enabled}, {"active", sv.active}};
    for (const auto& row : s.px4.params) {
      if (row.absent) absent.push_back(row.name);
      else if (!row.ok) wrong.push_back(row.name);
    }
    r.summary({{"ok", true},
               {"board", shell.describe()},
               {"ready", s.not_ready.empty()},
               {"not_ready", s.not_ready},
               {"packages", packages},
               {"services", services},
               {"vision_hub", keys_json(s.vision_hub)},
               {"vision_hub_hitl", s.vision_hub_hitl},
               {"vio_server", keys_json(s.vio_server)},
               {"record", s.record},
               {"px4",
                {{"heartbeat", s.px4.heartbeat},
                 {"error", s.px4.heartbeat ? nlohmann::json(nullptr) : nlohmann::json(s.px4.link_error)},
                 {"hil_mode", s.px4.hil_mode},
                 {"dsp_hitl_running", s.px4.dsp_hitl_running ? nlohmann::json(*s.px4.dsp_hitl_running) : nlohmann::json(nullptr)}}},
               {"params", {{"checked", s.px4.params_checked}, {"wrong", wrong}, {"absent", absent}}}});
    return kExitOk;
  }
  std::cout << "board: " << shell.describe() << '\n' << "packages (this build " << kVersion << "):\n";
  for (const auto& p : s.packages)
    std::cout << "  " << p.name << ": " << (p.installed.empty() ? "not installed" : p.installed) << (p.current() ? "" : "  (not this build's)") << '\n';
  std::cout << "services:\n";
  for (const auto& sv : s.services)
    std::cout << "  " << sv.name << ": " << (sv.enabled ? "enabled" : "disabled") << ", " << (sv.active ? "active" : "inactive") << '\n';
  std::cout << board::kVisionHubConf << ": " << keys_text(s.vision_hub) << '\n'
            << board::kVioServerConf << ": " << keys_text(s.vio_server) << '\n'
            << "install record: " << (s.record ? std::string("yes (hitl board restore goes back to it)") : std::string("none")) << '\n';
  if (s.px4.heartbeat) {
    std::cout << "PX4: HEARTBEAT, " << (s.px4.hil_mode ? "HIL mode" : "NOT in HIL mode") << ", dsp_hitl "
              << (s.px4.dsp_hitl_running ? (*s.px4.dsp_hitl_running ? "running" : "not running") : "did not answer") << '\n';
    if (s.px4.params_checked)
      std::cout << "HITL parameters: " << s.px4.params.size() - s.params_wrong - s.params_absent << " as the spec sets them, " << s.params_wrong
                << " differ, " << s.params_absent << " absent from this firmware\n";
  } else {
    std::cout << "PX4: " << s.px4.link_error << '\n';
  }
  if (s.not_ready.empty()) {
    std::cout << "ready for hitl sim\n";
  } else {
    std::cout << "not ready:\n";
    for (const auto& n : s.not_ready) std::cout << "  - " << n << '\n';
  }
  return kExitOk;
}

/// A dry run over the network touches nothing, `adb connect` included: the board must be connected
/// to adb already (`adb devices` lists IP:5555), and is read through that device.
Expected<net::Adb> connected_network_adb(const std::string& ip) {
  const std::string serial = ip + ":" + std::to_string(net::kAdbTcpPort);
  auto listed = net::list_adb_devices();
  if (!listed) return listed.error();
  for (const auto& d : listed->devices)
    if (d.serial == serial && d.ready()) return net::Adb::connect(serial);
  return Error::unavailable("a dry run does not run `adb connect " + serial + "` (it changes nothing), and adb has no device " + serial +
                            " connected: run `adb connect " + serial + "` first, or give --adb for USB");
}

int run_board(const GlobalOptions& g, const BoardOptions& o, const std::string& action) {
  const Reporter r{g, action};
  std::vector<board::PackageFile> packages;
  if (action == "install") {
    if (o.files.empty()) {
      auto built = board::build_packages(o.packages_dir, kVersion);
      if (!built) return r.error(built.error());
      packages = *built;
    }
    for (const auto& f : o.files) {
      auto p = board::local_package(f);
      if (!p) return r.error(p.error());
      packages.push_back(*p);
    }
  }
  if (o.network) {  // the address first: a name that does not resolve, or is no host at all, is refused before adb runs
    if (auto address = net::resolve_board_address(o.link.target_ip, net::kAdbTcpPort); !address) return r.error(address.error());
  }
  auto adb = !o.network ? net::Adb::connect(o.adb_serial) : o.dry_run ? connected_network_adb(o.link.target_ip) : net::Adb::connect_network(o.link.target_ip);
  if (!adb) return r.error(adb.error());
  board::AdbBoardShell shell(*adb);
  log_info(g, "hitl board " + action + ": " + shell.describe());
  auto survey = board::survey_board(shell);
  if (!survey) return r.error(survey.error().prefixed("reading the board: "));
  // Over USB with no -i/--connect, PX4's GCS instance is reached through the adb tunnel
  // (hitl-adb-relay, docs/adb.md), as hitl bridge --adb does; a dry run opens nothing.
  BoardOptions run = o;
  std::unique_ptr<net::AdbTunnel> tunnel;
  if ((action == "status" || (action == "start" && !o.dry_run)) && !o.network && !o.link_given) {
    auto opened = open_adb_tunnel(g, "board " + action, AdbOptions{true, o.adb_serial, ""});
    if (!opened) {
      if (action == "start")
        return r.error(opened.error().prefixed("reaching PX4 through adb (nothing was changed; or give -i IP / --connect): "));
      run.px4_unreachable = "no way to PX4 through adb: " + opened.error().message + " (or give -i IP / --connect)";
    } else {
      tunnel = std::move(opened.value());
      run.link.connect = "udp:" + tunnel->local_endpoint(adb::Channel::Gcs).to_string();
      log_info(g, "hitl board " + action + ": PX4 through " + tunnel->describe());
    }
  }
  if (action == "status") return run_status(g, run, r, shell, *survey);
  Expected<board::BoardPlan> plan = Error::usage("unknown action " + action);
  if (action == "install") plan = board::make_install_plan(*survey, {packages});
  if (action == "start") plan = board::make_start_plan(*survey, {o.reset_params, o.wait_s});
  if (action == "stop") plan = board::make_stop_plan(*survey);
  if (action == "restore") plan = board::make_restore_plan(*survey, {o.keep, o.params == "remove"});
  if (!plan) return r.error(plan.error());
  return run_plan_command(g, run, r, shell, *plan);
}

}  // namespace

void add_board_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto* sub = app.add_subcommand("board", "The VOXL2 for HITL over adb: install, start, stop, status, restore (docs/board.md)");
  sub->require_subcommand(1);
  sub->footer(
      "Every subcommand reads the board first (read-only), then runs its steps, saying each before it runs;\n"
      "--dry-run prints the steps with their exact board commands and changes nothing.\n"
      "The board's commands go through adb: over USB (--adb, the default; --adb-serial S), or with -i IP and\n"
      "no --adb over the network (adb connect IP:5555). start and status also talk MAVLink to PX4: at -i IP\n"
      "(or --connect), else through the adb tunnel (hitl-adb-relay on the board, as hitl bridge --adb).\n"
      "Exit: 0 done; 1 a step failed (what failed, what is already changed and how to undo it on stderr) or the\n"
      "board could not be reached (no adb, no device); 2 bad usage, a missing or misnamed package file.");
  auto o = std::make_shared<BoardOptions>();
  auto add = [&](const char* name, const char* help) {
    auto* c = sub->add_subcommand(name, help);
    c->add_flag("--adb", o->adb, "Run the board's commands through adb over USB (the default)")->group("Board");
    c->add_option("--adb-serial", o->adb_serial, "Which adb device is the board, when several are attached (implies --adb)")->group("Board");
    c->callback([&options, &state, o, c, action = std::string(name)]() {
      const CLI::Option* ip = c->get_option_no_throw("--target-ip");
      const CLI::Option* connect = c->get_option_no_throw("--connect");
      o->network = ip != nullptr && ip->count() > 0 && !o->adb && o->adb_serial.empty();
      o->link_given = (ip != nullptr && ip->count() > 0) || (connect != nullptr && connect->count() > 0);
      state.exit_code = run_board(options, *o, action);
    });
    return c;
  };
  // -i IP for the subcommands without the MAVLink options: the board's adb over the network.
  const auto add_ip = [&](CLI::App* c) {
    c->add_option("-i,--target-ip", o->link.target_ip, "The board's IP: its commands through adb over the network (adb connect IP:5555)")
        ->group("Board");
  };
  auto* install = add("install", "Push and install the HITL packages, write the vio-server config, set vision-hub's HITL keys (backup kept), enable the services");
  install->add_option("files", o->files, "Board .deb files to install instead of this build's (e.g. a voxl-fpv-px4 with HITL support)");
  install->add_option("--packages", o->packages_dir, "Where this build's board packages are (cpack's output, docs/board-packages.md)")
      ->capture_default_str();
  install->add_flag("--dry-run", o->dry_run, "Print the steps and their board commands; change nothing");
  add_ip(install);
  install->footer("Examples:\n  hitl board install --packages /tmp/board --dry-run\n  hitl board install --packages /tmp/board");

  auto* start = add("start", "Start PX4 in HITL, wait for its HEARTBEAT and dsp_hitl, set the HITL parameters, start the VIO server and vision-hub");
  start->add_flag("--reset-params", o->reset_params, "voxl-px4-hitl start --reset-params: load the HITL default parameters again");
  start->add_option("--wait", o->wait_s, "Seconds to wait for PX4's HEARTBEAT and dsp_hitl running")->capture_default_str()->check(positive_number());
  start->add_flag("--dry-run", o->dry_run, "Print the steps and their board commands; change nothing");
  add_link_options(start, o->link);
  start->footer("Examples:\n  hitl board start\n  hitl board start --adb -i 192.168.101.2 --reset-params");

  auto* stop = add("stop", "Stop vision-hub, the VIO server and PX4 in HITL");
  stop->add_flag("--dry-run", o->dry_run, "Print the steps and their board commands; change nothing");
  add_ip(stop);

  auto* status = add("status", "Packages against this build, services, the config keys, the install record, PX4's HIL mode and the HITL parameters");
  add_link_options(status, o->link);
  status->footer("Examples:\n  hitl board status\n  hitl --json board status | jq .not_ready");

  auto* restore = add("restore", "Back to the board before hitl board install: configuration from the backup, services as they were, packages removed");
  restore->add_flag("--keep", o->keep, "Keep the HITL packages installed");
  restore->add_option("--params", o->params, "PX4's HITL parameter file: keep it, or remove it (the next start loads the HITL defaults)")
      ->capture_default_str()->check(CLI::IsMember({"keep", "remove"}));
  restore->add_flag("--dry-run", o->dry_run, "Print the steps and their board commands; change nothing");
  add_ip(restore);
}

}  // namespace hitl::cli
