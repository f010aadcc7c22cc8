// hitl arm / hitl disarm: COMPONENT_ARM_DISARM with its ACK, the board's reasons in words, and
// success only once the board's HEARTBEAT shows the new state.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "base/common/clock.h"
#include "base/mavlink/enums.h"
#include "cli/commands.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "engine/vehicle/command_client.h"

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
    return kExitFailed;
  }
  log_info(g, std::string("hitl ") + cmd + ": autopilot " + std::to_string((*link)->target_sysid()) + " " + (*link)->description());
  vehicle::CommandClient client(**link);
  const double give_up_s = monotonic_s() + o.wait_s;
  Expected<vehicle::CommandOutcome> outcome = Error{"not sent"};
  for (;;) {
    outcome = client.send(mavlink::cmd::kComponentArmDisarm,
                          {arm ? 1.0f : 0.0f, o.force ? mavlink::cmd::kArmDisarmForceMagic : 0.0f, 0, 0, 0, 0, 0});
    if (!outcome) {
      log_error(cmd, outcome.error().message);
      return kExitFailed;
    }
    const double left_s = give_up_s - monotonic_s();
    if (outcome->accepted() || !outcome->pending() || left_s <= 0) break;
    // Still converging: say what it waits for, let a second pass (the link keeps its HEARTBEAT), retry.
    log_info(g, waiting_text(cmd, *outcome, left_s));
    (*link)->wait(std::min(1.0, left_s), [](const mavlink::Frame&) { return false; });
  }
  bool confirmed = false;
  if (outcome->accepted()) {
    confirmed = (*link)->wait(3.0, [&](const mavlink::Frame& f) {
      if (!f.is<mavlink::msg::Heartbeat>()) return false;
      return ((f.as<mavlink::msg::Heartbeat>().base_mode & mavlink::mode_flag::kSafetyArmed) != 0) == arm;
    });
  }
  const std::string verb = arm ? "Arming" : "Disarming";
  if (g.json) {
    print_json_line({{"type", "summary"},
                     {"command", cmd},
                     {"ok", confirmed},
                     {"result", vehicle::to_string(outcome->result)},
                     {"reason", outcome->accepted() ? "" : (outcome->statustexts.empty() ? "" : outcome->statustexts.back())},
                     {"statustexts", outcome->statustexts}});
  } else if (confirmed) {
    std::cout << (arm ? "armed" : "disarmed") << '\n';
  } else if (outcome->accepted()) {
    std::cout << verb << " accepted, but the HEARTBEAT did not show it within 3 s\n";
  } else {
    std::cout << verb << " " << outcome->text() << '\n';
  }
  return confirmed ? kExitOk : kExitFailed;
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
