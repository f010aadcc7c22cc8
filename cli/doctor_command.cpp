// hitl doctor: the spec's Troubleshooting list and Verification phases as checks (engine/doctor),
// a line each ([pass] / [warn] / [FAIL] / [skip], what it saw, the fix under a warning or failure),
// or with --json one object per check and a summary. Exit 0 when nothing failed, 1 otherwise.
#include <iostream>

#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "engine/doctor/check_catalog.h"
#include "engine/doctor/doctor.h"
#include "engine/hil/px4_vehicle_params.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/vehicle_file.h"

namespace hitl::cli {
namespace {

const char* tag(doctor::Verdict v) {
  switch (v) {
    case doctor::Verdict::Pass: return "[pass]";
    case doctor::Verdict::Skip: return "[skip]";
    case doctor::Verdict::Warn: return "[warn]";
    case doctor::Verdict::Fail: return "[FAIL]";
  }
  return "[?]";
}

const char* colour(doctor::Verdict v) {
  switch (v) {
    case doctor::Verdict::Pass: return "\033[32m";
    case doctor::Verdict::Skip: return "\033[2m";
    case doctor::Verdict::Warn: return "\033[33m";
    case doctor::Verdict::Fail: return "\033[1;31m";
  }
  return "";
}

nlohmann::json check_json(const doctor::CheckResult& r) {
  return {{"type", "check"},
          {"check", r.check},
          {"group", r.group},
          {"result", doctor::to_string(r.result)},
          {"saw", r.saw},
          {"fix", r.fix.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.fix)}};
}

/// --px4's own options: the parameters hitl sim --px4 gives PX4 for the session's vehicle and
/// --px4-param's, as hitl sim puts them together (engine/hil/px4_launch.cpp).
struct DoctorPx4Options {
  std::vector<std::string> params;  ///< --px4-param NAME=VALUE
  std::string vehicle_file;         ///< --vehicle FILE.json
};

Status read_px4_options(const DoctorPx4Options& p, doctor::DoctorOptions& o) {
  auto vehicle = p.vehicle_file.empty() ? Expected<sensors::VehicleFile>(sensors::default_vehicle_file())
                                        : sensors::load_vehicle_file(p.vehicle_file);
  if (!vehicle) return vehicle.error().prefixed("--vehicle: ");
  o.px4_expected_params = hil::px4_vehicle_params(vehicle->vehicle, model::default_world_config().gravity_m_s2);
  for (const auto& text : p.params) {
    auto param = px4::parse_px4_param(text);
    if (!param) return param.error().prefixed("--px4-param ");
    o.px4_expected_params.push_back(*param);
  }
  return Ok{};
}

int run_doctor(const GlobalOptions& g, const doctor::DoctorOptions& o) {
  const bool tty = !g.json && stdout_is_tty();
  std::string group;
  auto print = [&](const doctor::CheckResult& r) {
    if (g.json) {
      print_json_line(check_json(r));
      return;
    }
    if (r.group != group) {
      group = r.group;
      std::cout << (tty ? "\033[1m" : "") << group << (tty ? "\033[0m" : "") << '\n';
    }
    std::cout << "  " << (tty ? colour(r.result) : "") << tag(r.result) << (tty ? "\033[0m" : "") << ' '
              << doctor::check_info(r.check).title << ": " << r.saw << '\n';
    if (!r.fix.empty()) std::cout << "         fix: " << r.fix << '\n';
    std::cout << std::flush;
  };
  auto progress = [&](const std::string& line) {
    if (g.verbosity > 0) log_info(g, "hitl doctor: " + line);
  };
  log_info(g, "hitl doctor: board " + o.link.target_ip + " (GCS instance " + std::to_string(o.link.gcs_port) + ", HIL " +
                  std::to_string(o.hil_port) + (o.vio ? ", VIO " + std::to_string(o.vio_port) : "") + "), session 127.0.0.1:" +
                  std::to_string(o.link.session_port));
  const auto results = doctor::run_doctor(o, print, progress);
  const auto s = doctor::summarize(results);
  if (g.json) {
    nlohmann::json failed = nlohmann::json::array();
    for (const auto& r : results)
      if (r.result == doctor::Verdict::Fail) failed.push_back(r.check);
    print_json_line({{"type", "summary"},
                     {"checks", results.size()},
                     {"passed", s.passed},
                     {"warned", s.warned},
                     {"failed", s.failed},
                     {"skipped", s.skipped},
                     {"failed_checks", failed},
                     {"ok", s.ok()}});
  } else {
    std::cout << '\n'
              << results.size() << " checks: " << s.passed << " passed, " << s.warned << " warned, " << s.failed << " failed, "
              << s.skipped << " skipped" << (s.ok() ? "" : " -- see the fix under each failure") << '\n';
  }
  return s.ok() ? kExitOk : kExitFailed;
}

}  // namespace

void add_doctor_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<doctor::DoctorOptions>();
  auto px4_options = std::make_shared<DoctorPx4Options>();
  auto* sub = app.add_subcommand("doctor",
                                 "Check the whole HITL setup (host, link, board sensors, parameters, EKF2, arming, VIO, "
                                 "simulator): pass/warn/fail/skip with what was seen and the fix");
  add_link_options(sub, o->link);
  sub->add_option("--hil-port", o->hil_port, "The board's HIL MAVLink instance (only looked at, never talked to)")
      ->capture_default_str()->check(number_in(1, 65535));
  sub->add_option("--vio-port", o->vio_port, "voxl-hitl-vio-server's ODOMETRY port")->capture_default_str()->check(number_in(1, 65535));
  sub->add_flag("--no-vio", [o](std::int64_t) { o->vio = false; }, "VIO is not used: skip its checks");
  sub->add_flag("--adb", o->adb, "The board is on adb: check adb devices and run the VIO checks through adb shell");
  sub->add_option("--adb-serial", o->adb_serial, "Which adb device is the board (implies --adb)");
  sub->add_option("--px4", o->px4_dir,
                  "Also check a PX4 SITL build for hitl sim --px4 (DIR as hitl sim --px4 takes it): found, version, "
                  "lockstep, a free instance. A session's own PX4 is checked without it")
      ->type_name("DIR");
  sub->add_option("--px4-param", px4_options->params,
                  "The session's --px4-param, so that px4-params expects them over the vehicle's; repeatable")
      ->type_name("NAME=VALUE");
  sub->add_option("--vehicle", px4_options->vehicle_file, "The session's --vehicle, whose parameters px4-params expects")
      ->check(CLI::ExistingFile)->type_name("FILE.json");
  sub->add_option("--listen", o->listen_s, "Seconds to listen to the board and the session (rates need two reports)")
      ->capture_default_str()->check(number_in(1.2, 60.0));
  sub->footer(
      "Checks, in order (docs/doctor.md): host (route to the board, adb devices, ports), link (HEARTBEAT, HIL mode,\n"
      "mavlink status, HIL_ACTUATOR_CONTROLS rate, flags 0x0F, armed bit), board sensors (dsp_hitl counters), parameters\n"
      "(as hitl params check), EKF2, arming, VIO (ODOMETRY, voxl-hitl-vio-server, hitl_vio, en_hitl), simulator (session,\n"
      "paused, real-time factor, late ticks), PX4 SITL (the build with --px4 DIR, its instance, PX4 connected to the\n"
      "session, its parameters as hitl set them). Against a hitl sim --px4 session the VOXL2's own checks skip.\n"
      "Exit: 0 when nothing failed, 1 when a check failed.\n"
      "Examples:\n  hitl doctor -i 192.168.101.2\n  hitl doctor --adb\n  hitl doctor --px4 ~/px4/PX4-Autopilot\n  hitl --json doctor | jq -c 'select(.result == \"fail\")'");
  sub->callback([&options, &state, o, px4_options]() {
    if (auto read = read_px4_options(*px4_options, *o); !read) {
      state.exit_code = log_error("doctor", read.error());
      return;
    }
    state.exit_code = run_doctor(options, *o);
  });
}

}  // namespace hitl::cli
