// hitl arm / hitl disarm: the action API's arm / disarm (COMPONENT_ARM_DISARM with its ACK, success
// only once the board's HEARTBEAT shows the new state); the board's reasons in words, the exit code.
#include <cstdio>
#include <iostream>

#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "engine/vehicle/action.h"

namespace hitl::cli {
namespace {

std::string waiting_text(const char* cmd, const vehicle::CommandOutcome& o, double left_s) {
  char text[64];
  std::snprintf(text, sizeof text, " (retrying for %.0f s more)", left_s);
  return std::string("hitl ") + cmd + ": waiting for the board: " + o.text() + text;
}

struct ArmOptions {
  vehicle::LinkOptions link;
  bool force = false;
  double wait_s = 0;  ///< --wait: retry while the board's preflight checks are pending, up to this long
};

int run_arm(const GlobalOptions& g, const ArmOptions& o, bool arm) {
  const char* cmd = arm ? "arm" : "disarm";
  auto link = vehicle::VehicleLink::connect(o.link);
  if (!link) {
    log_error(cmd, link.error().message);
    return exit_code(link.error());
  }
  log_info(g, std::string("hitl ") + cmd + ": autopilot " + std::to_string((*link)->target_sysid()) + " " + (*link)->description());
  vehicle::Action action(**link);
  const auto waiting = [&](const vehicle::CommandOutcome& refusal, double left_s) { log_info(g, waiting_text(cmd, refusal, left_s)); };
  const auto outcome = arm ? action.arm(o.force, o.wait_s, waiting) : action.disarm(o.force, o.wait_s, waiting);
  if (!outcome.command) {  // no COMMAND_ACK at all
    log_error(cmd, outcome.error);
    return kExitFailed;
  }
  const vehicle::CommandOutcome& answer = *outcome.command;
  const std::string verb = arm ? "Arming" : "Disarming";
  if (g.json) {
    print_json_line({{"type", "summary"},
                     {"command", cmd},
                     {"ok", outcome.ok()},
                     {"result", vehicle::to_string(answer.result)},
                     {"reason", answer.accepted() ? "" : (answer.statustexts.empty() ? "" : answer.statustexts.back())},
                     {"statustexts", answer.statustexts}});
  } else if (outcome.ok()) {
    std::cout << (arm ? "armed" : "disarmed") << '\n';
  } else if (answer.accepted()) {
    std::cout << verb << " accepted, but the HEARTBEAT did not show it within 3 s\n";
  } else {
    std::cout << verb << " " << answer.text() << '\n';
  }
  return outcome.ok() ? kExitOk : kExitFailed;
}

}  // namespace

void add_arm_commands(CLI::App& app, GlobalOptions& options, RunState& state) {
  for (const bool arm : {true, false}) {
    auto o = std::make_shared<ArmOptions>();
    auto* sub = app.add_subcommand(arm ? "arm" : "disarm",
                                   arm ? "Arm the vehicle (exit 0 once the board shows it armed; a denial says why)"
                                       : "Disarm the vehicle (PX4 refuses in the air unless --force)");
    add_link_options(sub, o->link);
    sub->add_option("--wait", o->wait_s,
                    "Retry for up to S seconds while the board's preflight checks are pending (EKF alignment, GPS), "
                    "printing what it waits for; then fail with the last reason")
        ->type_name("S")->check(non_negative_number());
    sub->add_flag("--force", o->force, arm ? "Skip the preflight checks (PX4's 21196)" : "Disarm even in the air (PX4's 21196)");
    sub->callback([&options, &state, o, arm]() { state.exit_code = run_arm(options, *o, arm); });
  }
}

}  // namespace hitl::cli
