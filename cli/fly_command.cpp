// hitl fly takeoff | land | hold | trajectory: the action API (engine/vehicle/action.h) and
// fly_trajectory (engine/vehicle/trajectory_flight.h), with progress, their outcome as text or JSON,
// and the exit code.
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <map>

#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "cli/report_output.h"
#include "base/common/clock.h"
#include "engine/mavlink/tlog.h"
#include "engine/hil/session_config.h"
#include "engine/vehicle/action.h"
#include "engine/vehicle/trajectory_flight.h"

namespace hitl::cli {
namespace {

struct FlyOptions {
  vehicle::LinkOptions link;
  std::optional<double> alt_m;  ///< takeoff: metres above home (default: the board's MIS_TAKEOFF_ALT)
  double wait_s = 60;           ///< how long to wait for the outcome
  std::string trajectory_file;
  double rc_rate_hz = 20;
  vehicle::StickMode mode = vehicle::StickMode::Velocity;
  std::string record_path;  ///< trajectory --record FILE.tlog
  std::string report_path;  ///< trajectory --report FILE.html (records to FILE.tlog without --record)
};

int finish(const GlobalOptions& g, const char* action, bool ok, const std::string& text, nlohmann::json extra = {}) {
  if (g.json) {
    nlohmann::json j = {{"type", "summary"}, {"command", "fly"}, {"action", action}, {"ok", ok}, {"message", text}};
    for (auto& [k, v] : extra.items()) j[k] = v;
    print_json_line(j);
  } else {
    std::cout << text << '\n';
  }
  return ok ? kExitOk : kExitFailed;
}

/// The trajectory_rc pilot from the host, on the board's own estimate (vehicle::fly_trajectory).
int fly_trajectory(const GlobalOptions& g, const FlyOptions& o, vehicle::VehicleLink& link, vehicle::Trajectory trajectory) {
  vehicle::FlyTrajectoryOptions fo;
  fo.mode = o.mode;
  fo.rc_rate_hz = o.rc_rate_hz;
  fo.estimate_wait_s = o.wait_s;
  fo.truth_sysid = hil::kSimulatorSystemId;  // through a session: its ground truth
  fo.keep_trace = g.json;
  // --record / --report: what the link carried and the pilot's setpoints, as hitl sim -t records them.
  std::string record_path = o.record_path;
  if (record_path.empty() && !o.report_path.empty()) {
    const std::string ext = ".html";
    const auto& r = o.report_path;
    record_path = (r.size() > ext.size() && r.compare(r.size() - ext.size(), ext.size(), ext) == 0 ? r.substr(0, r.size() - ext.size()) : r) + ".tlog";
    log_info(g, "hitl fly: --report: recording to " + record_path);
  }
  std::optional<mavlink::TlogWriter> writer;
  if (!record_path.empty()) {
    auto w = mavlink::TlogWriter::open(record_path);
    if (!w) {
      log_error("fly", "--record: " + w.error().message);
      return exit_code(w.error());
    }
    writer.emplace(std::move(w.value()));
    fo.record = [&writer](std::span<const uint8_t> frame) {
      if (writer->ok()) writer->write(static_cast<uint64_t>(unix_time_ns() / 1000), frame);
    };
  }
  auto flown = vehicle::fly_trajectory(link, std::move(trajectory), fo, [&](const std::string& text) { log_info(g, "hitl fly: " + text); });
  std::optional<report::ReportResult> written;
  if (writer) {
    writer->flush();
    if (!writer->ok()) log_error("fly", "--record: " + writer->error() + "; the recording is incomplete");
    if (!o.report_path.empty()) {
      auto r = write_report_and_say(g, "fly", record_path, o.report_path);
      if (r) written = *r;
    }
  }
  const auto say_report = [&](int code) {
    if (written && !g.json) std::cout << written->html_path << std::endl;
    return (!o.report_path.empty() && !written) ? kExitFailed : code;
  };
  if (!flown) return say_report(finish(g, "trajectory", false, flown.error().message));
  const vehicle::FlightResult& r = *flown;
  nlohmann::json trace = nlohmann::json::array();
  for (const auto& point : r.trace) {
    nlohmann::json row = {{"t_s", point.t_s}, {"p_enu_m", point.p_ENU_m}};
    if (point.truth_p_ENU_m) row["truth_p_enu_m"] = *point.truth_p_ENU_m;
    trace.push_back(std::move(row));
  }
  const bool truth = r.truth_tracking.samples > 0;
  const auto or_null = [&](double v) { return truth ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return say_report(finish(g, "trajectory", r.ok(), r.text(),
                {{"report", written ? report_json(*written) : nlohmann::json(nullptr)},
                 {"state", vehicle::to_string(r.state)},
                 {"mode", vehicle::to_string(r.mode)},
                 {"rms_m", r.tracking.rms_m},
                 {"max_m", r.tracking.max_m},
                 {"samples", r.tracking.samples},
                 {"truth_rms_m", or_null(r.truth_tracking.rms_m)},
                 {"truth_max_m", or_null(r.truth_tracking.max_m)},
                 {"truth_samples", r.truth_tracking.samples},
                 {"trace", trace}}));
}

/// What an action's failure says: "Takeoff temporarily rejected: ...", or the missing answer.
std::string refusal_text(const char* verb, const vehicle::ActionOutcome& outcome) {
  return outcome.command ? std::string(verb) + " " + outcome.command->text() : outcome.error;
}

int run_fly(const GlobalOptions& g, const FlyOptions& o, const std::string& action) {
  std::optional<vehicle::Trajectory> trajectory;
  if (action == "trajectory") {  // a bad file is refused before anything is sent
    auto t = vehicle::Trajectory::load(o.trajectory_file);
    if (!t) {
      log_error("fly", t.error().message);
      return exit_code(t.error());
    }
    trajectory = std::move(t.value());
  }
  auto link = vehicle::VehicleLink::connect(o.link);
  if (!link) {
    log_error("fly", link.error().message);
    return exit_code(link.error());
  }
  log_info(g, "hitl fly " + action + ": autopilot " + std::to_string((*link)->target_sysid()) + " " + (*link)->description());
  if (trajectory) return fly_trajectory(g, o, **link, std::move(*trajectory));
  vehicle::Action vehicle(**link);
  const bool progress = ::isatty(STDERR_FILENO) == 1 && !g.quiet;

  if (action == "hold") {
    const auto r = vehicle.hold();
    if (r.result == vehicle::ActionResult::NotShown) return finish(g, "hold", false, "Hold accepted, but HEARTBEAT did not show it within 5 s");
    return finish(g, "hold", r.ok(), r.ok() ? "holding position" : refusal_text("Hold", r));
  }

  if (action == "takeoff") {
    // A refusal while the board's preflight checks are pending is retried within --wait, saying why.
    const auto waiting = [&](const vehicle::CommandOutcome& refusal, double) {
      log_info(g, "hitl fly takeoff: waiting for the board: " + refusal.text());
    };
    const double target_m = o.alt_m ? *o.alt_m : vehicle.default_takeoff_alt_m().value_or(2.5);
    const auto r = vehicle.takeoff(o.alt_m, o.wait_s, waiting);
    if (!r.ok()) return finish(g, "takeoff", false, refusal_text("Takeoff", r));
    const auto climbed = vehicle.wait_altitude(target_m, o.wait_s, [&](double alt_m) {
      if (progress) std::fprintf(stderr, "\raltitude %5.2f / %.2f m", alt_m, target_m);
    });
    if (progress) std::fprintf(stderr, "\n");
    const double alt_m = climbed.altitude_m.value_or(0.0);
    char text[128];
    std::snprintf(text, sizeof text, climbed.ok() ? "at %.2f m (target %.2f m)" : "only %.2f m of %.2f m after the timeout", alt_m, target_m);
    return finish(g, "takeoff", climbed.ok(), text, {{"altitude_m", alt_m}, {"target_m", target_m}});
  }

  // land: NAV_LAND, then wait for the board to detect the touchdown and disarm.
  const auto r = vehicle.land();
  if (!r.ok()) return finish(g, "land", false, refusal_text("Land", r));
  const auto landed = vehicle.wait_landed(o.wait_s, [&](double alt_m) {
    if (progress) std::fprintf(stderr, "\raltitude %5.2f m", alt_m);
  });
  if (progress) std::fprintf(stderr, "\n");
  return finish(g, "land", landed.ok(), landed.ok() ? "landed and disarmed" : "not disarmed after the timeout (still landing?)",
                {{"altitude_m", landed.altitude_m ? nlohmann::json(*landed.altitude_m) : nlohmann::json(nullptr)}});
}

}  // namespace

void add_fly_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<FlyOptions>();
  auto* sub = app.add_subcommand("fly", "Take off, land, hold or fly a trajectory file, and wait for the outcome");
  sub->require_subcommand(1);
  add_link_options(sub, o->link);
  sub->add_option("--wait", o->wait_s, "Seconds to wait for the outcome (takeoff: also retried while the board's preflight checks are pending)")->capture_default_str()->check(positive_number());
  sub->footer("Arm first (hitl arm). Exit: 0 the outcome was seen, 1 refused or timed out.");
  auto add = [&](const char* name, const char* help) {
    auto* c = sub->add_subcommand(name, help);
    c->callback([&options, &state, o, action = std::string(name)]() { state.exit_code = run_fly(options, *o, action); });
    return c;
  };
  add("takeoff", "NAV_TAKEOFF; done when the altitude is reached")
      ->add_option("--alt", o->alt_m, "Metres above home (default: the board's MIS_TAKEOFF_ALT)")->check(positive_number());
  add("land", "NAV_LAND; done when the board has landed and disarmed");
  add("hold", "Switch to Hold (PX4 AUTO.LOITER); done when HEARTBEAT shows it");
  auto* traj = add("trajectory",
                   "The spec's trajectory_rc automation from the host: arm, take off, fly the waypoints by stick "
                   "(RC_CHANNELS_OVERRIDE), hold, land, disarm; report the tracking error (--json: the trace)");
  traj->add_option("FILE", o->trajectory_file, "Waypoints {t, x, y, z, yaw} in ENU metres/radians")->required()
      ->check(CLI::ExistingFile);
  traj->add_option("--rate", o->rc_rate_hz, "RC_CHANNELS_OVERRIDE rate, Hz")->capture_default_str()->check(number_in(2.0, 100.0));
  traj->add_option("--mode", o->mode,
                   "velocity: Position mode, sticks are velocities; attitude: Stabilized, sticks are tilt and thrust "
                   "(the pilot closes position and velocity itself)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, vehicle::StickMode>{{"velocity", vehicle::StickMode::Velocity},
                                                                                  {"attitude", vehicle::StickMode::Attitude}}))
      ->default_str("velocity");
  traj->add_option("--record", o->record_path, "Save every frame read and sent, and the pilot's setpoints, to a .tlog")
      ->type_name("FILE.tlog");
  traj->add_option("--report", o->report_path,
                   "At the end, draw the recording as an HTML page (hitl report; docs/report.md); without --record, "
                   "records to FILE with .tlog")
      ->type_name("FILE.html");
}

}  // namespace hitl::cli
