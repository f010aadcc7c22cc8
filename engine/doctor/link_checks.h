// The link's part of the spec ("Verify MAVLink instance is running: mavlink status", "Verify
// HIL_ACTUATOR_CONTROLS stream is configured at 200 Hz", "Check msg.flags = 0x0F"): decisions on
// what doctor heard. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/contract/hil_actuators.h"
#include "engine/doctor/check_result.h"
#include "engine/doctor/observations.h"

namespace hitl::doctor {

using ::hitl::kVoxl2ActuatorFlags;  // base/contract/hil_actuators.h

/// heartbeat: `link` is how doctor reached the autopilot, or why it could not.
CheckResult heartbeat_check(const Expected<std::string>& link, const std::optional<HeartbeatSeen>& heartbeat);
/// hil-mode: HEARTBEAT.base_mode carries MAV_MODE_FLAG_HIL_ENABLED (SYS_HITL 1 at PX4's start).
CheckResult hil_mode_check(const std::optional<HeartbeatSeen>& heartbeat);

/// One instance of `mavlink status`: "instance #0" and its "UDP (14560, remote port: 14550)".
struct MavlinkInstanceSeen {
  int number = -1;
  std::optional<uint16_t> udp_port;
  std::string remote;  ///< "14550", "none", ...
};
/// Reads PX4's (and hitl target's) `mavlink status` text.
std::vector<MavlinkInstanceSeen> parse_mavlink_status(const std::string& text);
/// mavlink-instances: the HIL instance on `hil_port` among them. `output` is the shell's answer or
/// why there was none.
CheckResult mavlink_instances_check(const Expected<std::string>& output, uint16_t hil_port);

/// The rate HIL_ACTUATOR_CONTROLS should reach the simulator at, in wall-clock Hz: one answer per
/// HIL_SENSOR (250 Hz of simulated time, so 250 x the real-time factor) in lockstep, otherwise the
/// board's own 200 Hz stream. Nullopt when the session has not said enough yet.
std::optional<double> expected_actuator_rate_hz(const SessionStatus& session);
/// actuators: the rate the session measures against that.
CheckResult actuators_check(const SessionStatus& session);
/// actuator-flags: 0x0F.
CheckResult actuator_flags_check(const SessionStatus& session);
/// armed-state: the armed bit in HIL_ACTUATOR_CONTROLS.mode against HEARTBEAT's.
CheckResult armed_state_check(const SessionStatus& session, const std::optional<HeartbeatSeen>& heartbeat);

/// Why a check that needs the session is skipped when none answered.
std::string no_session_reason(uint16_t session_port);

}  // namespace hitl::doctor
