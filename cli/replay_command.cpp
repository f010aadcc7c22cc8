// hitl replay FILE.tlog: a recorded session's sensor and VIO streams to a board, open loop
// (engine/replay); --compare: how the board's actuator outputs differ from the recording's.
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/number_check.h"
#include "engine/replay/actuator_compare.h"
#include "engine/replay/recorded_session.h"
#include "engine/replay/replayer.h"

namespace hitl::cli {
namespace {

struct ReplayOptions {
  std::string file;
  replay::ReplayConfig config;
  bool compare = false;
  double tolerance = 0;
};

nlohmann::json comparison_json(const replay::ActuatorComparison& c) {
  nlohmann::json motors = nlohmann::json::array();
  for (const auto& m : c.motors) motors.push_back({{"max", m.max_abs}, {"rms", m.rms}});
  nlohmann::json j = {{"matched", c.by_echo ? "echo" : "step"}, {"steps_compared", c.steps_compared},
                      {"missing", c.missing},                  {"identical", c.identical()},
                      {"motors", motors},                      {"first_divergence", nullptr}};
  if (const auto& d = c.first_divergence)
    j["first_divergence"] = {{"t_s", d->t_s}, {"motor", d->motor}, {"recorded", d->recorded}, {"replayed", d->replayed}};
  return j;
}

void print_comparison(const replay::ActuatorComparison& c, double tolerance) {
  std::printf("actuator outputs against the recording (%s, %llu steps compared%s):\n",
              c.by_echo ? "matched by time_usec echo" : "matched by step", static_cast<unsigned long long>(c.steps_compared),
              c.missing ? (", " + std::to_string(c.missing) + " unanswered in the replay").c_str() : "");
  std::printf("%-6s %12s %12s\n", "MOTOR", "MAX DIFF", "RMS DIFF");
  for (std::size_t i = 0; i < c.motors.size(); ++i) std::printf("%-6zu %12.6f %12.6f\n", i, c.motors[i].max_abs, c.motors[i].rms);
  if (const auto& d = c.first_divergence)
    std::printf("first divergence at t = %.3f s: motor %d %.6f recorded, %.6f replayed (tolerance %g)\n", d->t_s, d->motor,
                d->recorded, d->replayed, tolerance);
  else if (c.missing == 0)
    std::printf("identical%s\n", tolerance > 0 ? (" within " + std::to_string(tolerance)).c_str() : " (bit for bit)");
}

int run_replay(const GlobalOptions& global, const ReplayOptions& opt) {
  const char* cmd = "replay";
  auto session = replay::load_recording(opt.file);
  if (!session) {
    log_error(cmd, session.error().message);
    return exit_code(session.error());
  }
  if (opt.compare && session->actuators.empty()) {
    return log_error(cmd, Error::input("--compare: recording '" + opt.file + "' holds no HIL_ACTUATOR_CONTROLS to compare with"));
  }
  char line[512];
  std::snprintf(line, sizeof line,
                "hitl replay: %zu steps (%.1f s simulated) from %s to %s:%u%s, %s (Ctrl-C to stop)", session->steps.size(),
                session->duration_s(), opt.file.c_str(), opt.config.target_ip.c_str(), opt.config.hil_port,
                session->vio_frames && opt.config.vio_port ? (", ODOMETRY to port " + std::to_string(opt.config.vio_port)).c_str() : "",
                opt.config.lockstep ? "lockstep (each step waits for its answer)" : "with the recorded timing");
  log_info(global, line);
  if (!opt.config.lockstep && session->steps.size() > 1) {
    const double wall_s = static_cast<double>(session->steps.back().t_unix_us - session->steps.front().t_unix_us) * 1e-6;
    const double pace = wall_s > 0 ? session->duration_s() / wall_s : 0;
    if (pace > 1.1 || pace < 0.9) {
      std::snprintf(line, sizeof line,
                    "the recording ran at %.1fx real time (%.1f s simulated in %.1f s): replaying it with that timing; "
                    "a board on its own clock sees its sensors at that pace (--lockstep replays step by step)",
                    pace, session->duration_s(), wall_s);
      std::cerr << "hitl replay: warning: " << line << '\n';
    }
  }
  const auto& stop = stop_flag_on_signals();
  auto result = replay::run_replay(*session, opt.config, stop, [&](const replay::ReplayProgress& p) {
    if (global.json) {
      print_json_line({{"type", "status"}, {"step", p.step}, {"steps", p.steps}, {"sim_time_s", p.sim_time_s},
                       {"answers", p.answers}, {"fallbacks", p.fallbacks}});
    } else if (!global.quiet) {
      std::fprintf(stderr, "step %llu of %llu  t %.1f s  answers %llu  lockstep fallbacks %llu\n",
                   static_cast<unsigned long long>(p.step), static_cast<unsigned long long>(p.steps), p.sim_time_s,
                   static_cast<unsigned long long>(p.answers), static_cast<unsigned long long>(p.fallbacks));
    }
  });
  if (!result) {
    log_error(cmd, result.error().message);
    return exit_code(result.error());
  }
  std::optional<replay::ActuatorComparison> comparison;
  if (opt.compare) comparison = replay::compare_actuators(session->steps, session->actuators, result->actuators, opt.tolerance);
  const bool diverged = comparison && !comparison->identical();
  if (global.json) {
    nlohmann::json j = {{"type", "summary"},
                        {"end", result->stopped ? "stopped" : "done"},
                        {"file", opt.file},
                        {"lockstep", opt.config.lockstep},
                        {"steps", session->steps.size()},
                        {"steps_sent", result->steps_sent},
                        {"frames_sent", result->frames_sent},
                        {"answers", result->answers},
                        {"fallbacks", result->fallbacks},
                        {"sim_time_s", session->duration_s()},
                        {"wall_time_s", result->wall_time_s}};
    if (comparison) j["compare"] = comparison_json(*comparison);
    print_json_line(j);
  } else {
    std::printf("replayed %llu of %zu steps (%llu frames) in %.1f s wall: %llu HIL_ACTUATOR_CONTROLS back, %llu lockstep fallbacks%s\n",
                static_cast<unsigned long long>(result->steps_sent), session->steps.size(),
                static_cast<unsigned long long>(result->frames_sent), result->wall_time_s,
                static_cast<unsigned long long>(result->answers), static_cast<unsigned long long>(result->fallbacks),
                result->stopped ? " (stopped)" : "");
    if (comparison) print_comparison(*comparison, opt.tolerance);
  }
  if (result->answers == 0) {
    log_error(cmd, "no HIL_ACTUATOR_CONTROLS came back from " + opt.config.target_ip + ":" + std::to_string(opt.config.hil_port));
    return kExitFailed;
  }
  return diverged ? kExitFailed : kExitOk;
}

}  // namespace

void add_replay_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto opt = std::make_shared<ReplayOptions>();
  auto* sub = app.add_subcommand("replay", "Send a recorded session's sensor and VIO streams to a board and compare its answers");
  sub->footer(
      "Open loop: the board gets what the recording sent it (HIL_SENSOR, HIL_GPS, the pilot's commands, ODOMETRY),\n"
      "with the recorded timing, or with --lockstep one step at a time. docs/replay.md.\n"
      "Example:  hitl sim --lockstep --speed 0 -t square.json --record square.tlog\n"
      "          hitl replay square.tlog --lockstep --compare   # exit 1 when the board answers differently");
  sub->add_option("FILE.tlog", opt->file, "A hitl sim recording (hitl sim --record)")->required()->type_name("FILE.tlog");
  auto& c = opt->config;
  sub->add_option("-i,--target-ip", c.target_ip, "The board's IP address")->capture_default_str();
  sub->add_option("--hil-port", c.hil_port, "The board's HIL MAVLink port")->capture_default_str()->check(number_in(1, 65535));
  sub->add_option("--vio-port", c.vio_port, "voxl-hitl-vio-server's port for the recorded ODOMETRY (0: none)")
      ->capture_default_str()->check(number_in(0, 65535));
  sub->add_option("--local-port", c.local_port, "Local UDP port of the HIL link: the simulator's, since a board answers only the first port it heard (0: any)")
      ->capture_default_str()->check(number_in(0, 65535));
  sub->add_option("--bind", c.bind_address, "Local address for the replay's sockets")->capture_default_str();
  sub->add_flag("--lockstep", c.lockstep, "Send a step only after the board answered the last (hitl target --lockstep)");
  sub->add_option("--lockstep-timeout", c.lockstep_timeout_s, "Seconds to wait for a step's answer before going on")
      ->capture_default_str()->check(positive_number())->type_name("S");
  sub->add_option("--record", c.record_path, "Save everything sent and received to a .tlog")->type_name("FILE.tlog");
  sub->add_flag("--compare", opt->compare,
                "Report how the board's HIL_ACTUATOR_CONTROLS differ from the recording's (exit 1 when they do)");
  sub->add_option("--tolerance", opt->tolerance, "--compare: a motor differs when by more than this (0: any bit)")
      ->capture_default_str()->check(non_negative_number());
  sub->callback([&options, &state, opt]() { state.exit_code = run_replay(options, *opt); });
}

}  // namespace hitl::cli
