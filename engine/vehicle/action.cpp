#include "engine/vehicle/action.h"

#include <algorithm>
#include <cmath>

#include "base/common/clock.h"
#include "base/mavlink/enums.h"
#include "engine/vehicle/param_client.h"

namespace hitl::vehicle {
namespace {
namespace msg = mavlink::msg;

constexpr float kUnset = NAN;  ///< a reserved or defaulted COMMAND_LONG parameter
constexpr float kCustomModeEnabled = 1;  ///< DO_SET_MODE param1: MAV_MODE_FLAG_CUSTOM_MODE_ENABLED

bool never(const mavlink::Frame&) { return false; }

}  // namespace

CommandRequest arm_request(bool force) {
  return {mavlink::cmd::kComponentArmDisarm, {1, force ? mavlink::cmd::kArmDisarmForceMagic : 0.0f, 0, 0, 0, 0, 0}};
}

CommandRequest disarm_request(bool force) {
  return {mavlink::cmd::kComponentArmDisarm, {0, force ? mavlink::cmd::kArmDisarmForceMagic : 0.0f, 0, 0, 0, 0, 0}};
}

CommandRequest takeoff_request(std::optional<double> alt_amsl_m) {
  return {mavlink::cmd::kNavTakeoff, {0, 0, 0, kUnset, kUnset, kUnset, alt_amsl_m ? static_cast<float>(*alt_amsl_m) : kUnset}};
}

CommandRequest land_request() { return {mavlink::cmd::kNavLand, {0, 0, 0, kUnset, kUnset, kUnset, kUnset}}; }

CommandRequest set_mode_request(Px4Mode mode) {
  return {mavlink::cmd::kDoSetMode, {kCustomModeEnabled, static_cast<float>(mode.main), static_cast<float>(mode.sub), 0, 0, 0, 0}};
}

bool shows_armed(const msg::Heartbeat& heartbeat) { return (heartbeat.base_mode & mavlink::mode_flag::kSafetyArmed) != 0; }

const char* to_string(ActionResult r) {
  switch (r) {
    case ActionResult::Success: return "success";
    case ActionResult::Refused: return "refused";
    case ActionResult::NoAnswer: return "no answer";
    case ActionResult::NotShown: return "not shown";
    case ActionResult::NoPosition: return "no position";
  }
  return "?";
}

ActionOutcome Action::command(const CommandRequest& request, double retry_s, const Waiting& waiting) {
  const double give_up_s = monotonic_s() + retry_s;
  for (;;) {
    auto sent = commands_.send(request);
    if (!sent) return {ActionResult::NoAnswer, std::nullopt, sent.error().message, std::nullopt};
    const double left_s = give_up_s - monotonic_s();
    if (sent->accepted() || !sent->pending() || left_s <= 0)
      return {sent->accepted() ? ActionResult::Success : ActionResult::Refused, std::move(sent.value()), "", std::nullopt};
    // Still converging: say what it waits for, let a second pass (the link keeps its HEARTBEAT), retry.
    if (waiting) waiting(*sent, left_s);
    link_.wait(std::min(1.0, left_s), never);
  }
}

ActionOutcome Action::arm_disarm(bool arm, bool force, double retry_s, const Waiting& waiting) {
  auto outcome = command(arm ? arm_request(force) : disarm_request(force), retry_s, waiting);
  if (!outcome.ok()) return outcome;
  const bool shown = link_.wait(kShowArmed_s, [&](const mavlink::Frame& f) {
    return f.is<msg::Heartbeat>() && shows_armed(f.as<msg::Heartbeat>()) == arm;
  });
  if (!shown) outcome.result = ActionResult::NotShown;
  return outcome;
}

ActionOutcome Action::arm(bool force, double retry_s, const Waiting& waiting) { return arm_disarm(true, force, retry_s, waiting); }

ActionOutcome Action::disarm(bool force, double retry_s, const Waiting& waiting) {
  return arm_disarm(false, force, retry_s, waiting);
}

ActionOutcome Action::takeoff(std::optional<double> alt_m, double retry_s, const Waiting& waiting) {
  std::optional<double> alt_amsl_m;
  if (alt_m) {  // NAV_TAKEOFF's altitude is AMSL: home's from GLOBAL_POSITION_INT
    const auto home_m = home_amsl_m();
    if (!home_m)
      return {ActionResult::NoPosition, std::nullopt, "no GLOBAL_POSITION_INT from the board: is its position estimate valid?",
              std::nullopt};
    alt_amsl_m = *home_m + *alt_m;
  }
  return command(takeoff_request(alt_amsl_m), retry_s, waiting);
}

ActionOutcome Action::land() { return command(land_request(), 0, {}); }

ActionOutcome Action::set_mode(Px4Mode mode) {
  auto outcome = command(set_mode_request(mode), 0, {});
  if (!outcome.ok()) return outcome;
  const bool shown = link_.wait(kShowMode_s, [&](const mavlink::Frame& f) {
    return f.is<msg::Heartbeat>() && f.as<msg::Heartbeat>().custom_mode == mode.custom_mode();
  });
  if (!shown) outcome.result = ActionResult::NotShown;
  return outcome;
}

ActionOutcome Action::wait_altitude(double target_m, double timeout_s, const Altitude& progress, double tolerance_m) {
  ActionOutcome outcome{ActionResult::NotShown, std::nullopt, "", std::nullopt};
  const bool reached = link_.wait(timeout_s, [&](const mavlink::Frame& f) {
    if (!f.is<msg::GlobalPositionInt>()) return false;
    const double alt_m = f.as<msg::GlobalPositionInt>().relative_alt / 1000.0;
    outcome.altitude_m = alt_m;
    if (progress) progress(alt_m);
    return alt_m >= target_m - tolerance_m;
  });
  if (reached) outcome.result = ActionResult::Success;
  return outcome;
}

ActionOutcome Action::wait_landed(double timeout_s, const Altitude& progress) {
  ActionOutcome outcome{ActionResult::NotShown, std::nullopt, "", std::nullopt};
  const bool disarmed = link_.wait(timeout_s, [&](const mavlink::Frame& f) {
    if (f.is<msg::GlobalPositionInt>()) {
      outcome.altitude_m = f.as<msg::GlobalPositionInt>().relative_alt / 1000.0;
      if (progress) progress(*outcome.altitude_m);
    }
    return f.is<msg::Heartbeat>() && !shows_armed(f.as<msg::Heartbeat>());
  });
  if (disarmed) outcome.result = ActionResult::Success;
  return outcome;
}

std::optional<double> Action::home_amsl_m(double timeout_s) {
  std::optional<double> home_m;
  link_.wait(timeout_s, [&](const mavlink::Frame& f) {
    if (!f.is<msg::GlobalPositionInt>()) return false;
    const auto p = f.as<msg::GlobalPositionInt>();
    home_m = (p.alt - p.relative_alt) / 1000.0;
    return true;
  });
  return home_m;
}

std::optional<double> Action::default_takeoff_alt_m() {
  if (auto p = ParamClient(link_).get("MIS_TAKEOFF_ALT")) return p->as_double();
  return std::nullopt;
}

}  // namespace hitl::vehicle
