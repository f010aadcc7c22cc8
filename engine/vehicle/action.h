// The vehicle's actions as one API, as MAVSDK's Action plugin: arm, disarm, takeoff, land, hold,
// set mode. Each is written once, in two halves:
//   the request: the COMMAND_LONG the action takes (pure; the trajectory pilot sends these from its
//     own loop, which never blocks);
//   the blocking call on a VehicleLink: the request through CommandClient (retries, the ACK, the
//     board's STATUSTEXT as the reason), a refusal that goes away by itself retried when asked,
//     then the wait for what the board shows (HEARTBEAT armed or in the mode).
// And the waits that follow a takeoff or a landing (the altitude reached; landed and disarmed).
// `hitl arm` / `hitl disarm`, `hitl fly`, the dashboard's command worker and fly_trajectory() all
// act through here. Each outcome is a word plus the board's own answer (CommandOutcome); callers
// turn it into text.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "base/mavlink/messages.h"
#include "engine/vehicle/command_client.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

/// A PX4 mode as DO_SET_MODE's main and sub mode (param2, param3); HEARTBEAT's custom_mode shows
/// it as main << 16 | sub << 24.
struct Px4Mode {
  uint8_t main = 0;
  uint8_t sub = 0;
  constexpr uint32_t custom_mode() const { return static_cast<uint32_t>(main) << 16 | static_cast<uint32_t>(sub) << 24; }
};
inline constexpr Px4Mode kPx4Position{3, 0};    ///< POSCTL: sticks are velocities
inline constexpr Px4Mode kPx4Stabilized{7, 0};  ///< STABILIZED: sticks are tilt and thrust
inline constexpr Px4Mode kPx4Hold{4, 3};        ///< AUTO.LOITER
inline constexpr Px4Mode kPx4Takeoff{4, 2};     ///< AUTO.TAKEOFF

// --- the requests ---------------------------------------------------------------------------
/// COMPONENT_ARM_DISARM; `force` skips the preflight checks (arm) or disarms in the air (PX4's 21196).
CommandRequest arm_request(bool force = false);
CommandRequest disarm_request(bool force = false);
/// NAV_TAKEOFF to `alt_amsl_m` (none: the board's MIS_TAKEOFF_ALT above home).
CommandRequest takeoff_request(std::optional<double> alt_amsl_m = std::nullopt);
/// NAV_LAND where the vehicle is.
CommandRequest land_request();
/// DO_SET_MODE with the custom-mode flag.
CommandRequest set_mode_request(Px4Mode mode);

/// HEARTBEAT's armed flag.
bool shows_armed(const mavlink::msg::Heartbeat& heartbeat);

// --- the outcomes ---------------------------------------------------------------------------
enum class ActionResult {
  Success,     ///< accepted, and the board shows it (armed, the mode, the altitude, landed)
  Refused,     ///< the board answered with anything but ACCEPTED: `command` has its word and reason
  NoAnswer,    ///< no COMMAND_ACK after the retries: `error` says so
  NotShown,    ///< accepted (or waited for), but the board did not show the outcome in time
  NoPosition,  ///< a takeoff to an altitude above home without GLOBAL_POSITION_INT to find home
};
const char* to_string(ActionResult result);  ///< "success", "refused", "no answer", "not shown", "no position"

struct ActionOutcome {
  ActionResult result = ActionResult::NoAnswer;
  std::optional<CommandOutcome> command;  ///< the board's answer, when it gave one
  std::string error;                      ///< NoAnswer, NoPosition: what is missing, in words
  std::optional<double> altitude_m;       ///< the waits: the last altitude above home seen
  bool ok() const { return result == ActionResult::Success; }
};

// --- the blocking calls ---------------------------------------------------------------------
class Action {
 public:
  /// A refusal that goes away by itself (CommandOutcome::pending) before it is retried, with the
  /// seconds of retrying left.
  using Waiting = std::function<void(const CommandOutcome& refusal, double left_s)>;
  /// Each altitude above home seen during a wait (GLOBAL_POSITION_INT's relative_alt).
  using Altitude = std::function<void(double alt_m)>;

  static constexpr double kShowArmed_s = 3.0;  ///< how long HEARTBEAT may take to show an accepted arm/disarm
  static constexpr double kShowMode_s = 5.0;   ///< and a mode
  static constexpr double kHome_s = 3.0;       ///< how long to wait for GLOBAL_POSITION_INT to find home

  explicit Action(VehicleLink& link) : link_(link), commands_(link) {}

  /// Success once HEARTBEAT shows the vehicle armed; pending refusals retried for up to `retry_s`.
  ActionOutcome arm(bool force = false, double retry_s = 0, const Waiting& waiting = {});
  /// Success once HEARTBEAT shows it disarmed.
  ActionOutcome disarm(bool force = false, double retry_s = 0, const Waiting& waiting = {});
  /// NAV_TAKEOFF to `alt_m` above home (none: the board's MIS_TAKEOFF_ALT); success once accepted
  /// (wait_altitude() follows it); pending refusals retried for up to `retry_s`.
  ActionOutcome takeoff(std::optional<double> alt_m = std::nullopt, double retry_s = 0, const Waiting& waiting = {});
  /// NAV_LAND; success once accepted (wait_landed() follows it).
  ActionOutcome land();
  /// DO_SET_MODE; success once HEARTBEAT shows the mode.
  ActionOutcome set_mode(Px4Mode mode);
  ActionOutcome hold() { return set_mode(kPx4Hold); }

  /// Success once the altitude above home is within `tolerance_m` below `target_m`, else NotShown
  /// after `timeout_s`.
  ActionOutcome wait_altitude(double target_m, double timeout_s, const Altitude& progress = {}, double tolerance_m = 0.3);
  /// Success once HEARTBEAT shows the vehicle disarmed (PX4 disarms itself after a touchdown), else
  /// NotShown after `timeout_s`.
  ActionOutcome wait_landed(double timeout_s, const Altitude& progress = {});
  /// Home's altitude above mean sea level (GLOBAL_POSITION_INT alt - relative_alt), waiting up to `timeout_s`.
  std::optional<double> home_amsl_m(double timeout_s = kHome_s);
  /// The board's MIS_TAKEOFF_ALT, the height a takeoff without an altitude goes to.
  std::optional<double> default_takeoff_alt_m();

 private:
  /// Sends `request`, retrying pending refusals for up to `retry_s`; Success when accepted.
  ActionOutcome command(const CommandRequest& request, double retry_s, const Waiting& waiting);
  ActionOutcome arm_disarm(bool arm, bool force, double retry_s, const Waiting& waiting);

  VehicleLink& link_;
  CommandClient commands_;
};

}  // namespace hitl::vehicle
