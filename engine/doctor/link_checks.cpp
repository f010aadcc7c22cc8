#include "engine/doctor/link_checks.h"

#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>

#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "engine/doctor/check_catalog.h"
#include "engine/telemetry/px4_mode.h"

namespace hitl::doctor {
namespace {

std::string hex(uint32_t v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

const char* kRestartPx4 = "adb shell voxl-px4-hitl start";

}  // namespace

std::string no_session_reason(uint16_t session_port) {
  return "no hitl sim session answers on 127.0.0.1:" + std::to_string(session_port) +
         " (HIL_ACTUATOR_CONTROLS go only to the simulator that owns the HIL link; doctor never talks to the HIL "
         "port itself, PX4 would lock onto it)";
}

CheckResult heartbeat_check(const Expected<std::string>& link, const std::optional<HeartbeatSeen>& heartbeat) {
  if (!link)
    return make_result(check::kHeartbeat, Verdict::Fail, link.error().message,
                       "start PX4 on the board (" + std::string(kRestartPx4) + ") or the emulated board (hitl target); "
                       "check -i and --port");
  if (!heartbeat)
    return make_result(check::kHeartbeat, Verdict::Fail, "connected " + link.value() + " but no HEARTBEAT followed",
                       std::string("restart PX4 on the board: ") + kRestartPx4);
  const double span_s = heartbeat->last_s - heartbeat->first_s;
  std::string rate = heartbeat->count >= 2 && span_s > 0
                         ? ", " + fixed(static_cast<double>(heartbeat->count - 1) / span_s, 1) + " Hz"
                         : "";
  const bool px4 = heartbeat->autopilot == static_cast<uint8_t>(mavlink::MavAutopilot::Px4);
  return make_result(check::kHeartbeat, Verdict::Pass,
                     std::string(px4 ? "PX4" : "autopilot " + std::to_string(heartbeat->autopilot)) + " system " +
                         std::to_string(heartbeat->sysid) + " " + link.value() + rate + ", mode " +
                         telemetry::px4_mode_name(heartbeat->base_mode, heartbeat->custom_mode) +
                         (heartbeat->armed() ? ", armed" : ", disarmed"));
}

CheckResult hil_mode_check(const std::optional<HeartbeatSeen>& heartbeat) {
  if (!heartbeat) return make_result(check::kHilMode, Verdict::Skip, "no HEARTBEAT from the board");
  const std::string mode = "HEARTBEAT base_mode " + hex(heartbeat->base_mode, 2);
  if ((heartbeat->base_mode & mavlink::mode_flag::kHilEnabled) != 0)
    return make_result(check::kHilMode, Verdict::Pass, mode + " has MAV_MODE_FLAG_HIL_ENABLED");
  return make_result(check::kHilMode, Verdict::Fail,
                     mode + " lacks MAV_MODE_FLAG_HIL_ENABLED: PX4 runs without HIL and ignores HIL_SENSOR",
                     std::string("hitl params set SYS_HITL 1, then restart PX4 (it reads SYS_HITL at start): ") + kRestartPx4);
}

std::vector<MavlinkInstanceSeen> parse_mavlink_status(const std::string& text) {
  static const std::regex instance_re(R"(instance #(\d+))");
  static const std::regex udp_re(R"(UDP \((\d+), remote port: ([^)\s]+)\))");
  std::vector<MavlinkInstanceSeen> out;
  std::istringstream in(text);
  std::string line;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, instance_re)) {
      MavlinkInstanceSeen i;
      i.number = std::stoi(m[1].str().substr(0, 6));
      out.push_back(i);
    } else if (!out.empty() && !out.back().udp_port && std::regex_search(line, m, udp_re)) {
      const long port = std::stol(m[1].str().substr(0, 6));
      if (port > 0 && port <= 65535) out.back().udp_port = static_cast<uint16_t>(port);
      out.back().remote = m[2].str();
    }
  }
  return out;
}

CheckResult mavlink_instances_check(const Expected<std::string>& output, uint16_t hil_port) {
  if (!output)
    return make_result(check::kMavlinkInstances, Verdict::Warn, "mavlink status did not answer: " + output.error().message,
                       "hitl shell -c \"mavlink status\"");
  const auto instances = parse_mavlink_status(output.value());
  if (instances.empty())
    return make_result(check::kMavlinkInstances, Verdict::Warn,
                       "mavlink status printed no instance: '" + output.value().substr(0, 120) + "'", "hitl shell -c \"mavlink status\"");
  std::string list;
  bool hil = false;
  for (const auto& i : instances) {
    list += (list.empty() ? "" : ", ") + std::string("#") + std::to_string(i.number) +
            (i.udp_port ? " UDP " + std::to_string(*i.udp_port) + " (remote " + i.remote + ")" : " (not UDP)");
    hil = hil || (i.udp_port && *i.udp_port == hil_port);
  }
  if (hil) return make_result(check::kMavlinkInstances, Verdict::Pass, std::to_string(instances.size()) + " instances: " + list);
  return make_result(check::kMavlinkInstances, Verdict::Fail,
                     "no instance on the HIL port UDP " + std::to_string(hil_port) + "; instances: " + list,
                     std::string("restart PX4 HITL, whose start script starts the HIL instance on ") + std::to_string(hil_port) +
                         ": " + kRestartPx4);
}

std::optional<double> expected_actuator_rate_hz(const SessionStatus& s) {
  if (!s.lockstep) return std::nullopt;
  if (!*s.lockstep) return hitl::kActuatorStreamRate_hz;
  if (!s.rtf) return std::nullopt;
  return *s.rtf / hitl::kStepPeriod_s;
}

CheckResult actuators_check(const SessionStatus& s) {
  if (!s.heard() || !s.actuator_hz) return make_result(check::kActuators, Verdict::Skip, "the session did not report actuators");
  const double hz = *s.actuator_hz;
  const auto expected = expected_actuator_rate_hz(s);
  const std::string exp_text = expected ? " (expected " + fixed(*expected, 0) +
                                              (s.lockstep && *s.lockstep ? " Hz: one per HIL_SENSOR in lockstep)" : " Hz)")
                                        : "";
  const std::string stream_fix =
      "configure the stream on the board (the start script does): hitl shell -c \"mavlink stream -u 14560 -s "
      "HIL_ACTUATOR_CONTROLS -r 200\"; if PX4 answers an earlier simulator's port, restart it: " + std::string(kRestartPx4);
  if (!(hz > 0))
    return make_result(check::kActuators, Verdict::Fail,
                       std::string("no HIL_ACTUATOR_CONTROLS reached the simulator in the last second") +
                           (s.actuator_flags && *s.actuator_flags < 0 ? " (none ever)" : " (they stopped)"),
                       stream_fix);
  const std::string saw = fixed(hz, 0) + " Hz" + exp_text;
  if (!expected || !(*expected > 0)) return make_result(check::kActuators, Verdict::Pass, saw);
  const double ratio = hz / *expected;
  if (ratio >= 0.8 && ratio <= 1.2) return make_result(check::kActuators, Verdict::Pass, saw);
  if (ratio >= 0.5 && ratio <= 2.0)
    return make_result(check::kActuators, Verdict::Warn, saw, "a loaded board or link; " + stream_fix);
  return make_result(check::kActuators, Verdict::Fail, saw, stream_fix);
}

CheckResult actuator_flags_check(const SessionStatus& s) {
  if (!s.heard() || !s.actuator_flags) return make_result(check::kActuatorFlags, Verdict::Skip, "the session did not report actuators");
  if (*s.actuator_flags < 0) return make_result(check::kActuatorFlags, Verdict::Skip, "no HIL_ACTUATOR_CONTROLS received yet");
  const std::string saw = "flags " + hex(static_cast<uint32_t>(*s.actuator_flags), 2);
  if (static_cast<uint64_t>(*s.actuator_flags) == kVoxl2ActuatorFlags) return make_result(check::kActuatorFlags, Verdict::Pass, saw + " (motors 0-3)");
  return make_result(check::kActuatorFlags, Verdict::Fail, saw + ", not 0x0F (the VOXL2's quad bitmask, motors 0-3)",
                     "deploy a voxl-fpv-px4 built with HITL support (its HIL_ACTUATOR_CONTROLS set flags = 0x0F), then: " +
                         std::string(kRestartPx4));
}

CheckResult armed_state_check(const SessionStatus& s, const std::optional<HeartbeatSeen>& heartbeat) {
  if (!heartbeat) return make_result(check::kArmedState, Verdict::Skip, "no HEARTBEAT from the board");
  if (!s.heard() || !s.actuator_armed) return make_result(check::kArmedState, Verdict::Skip, "the session did not report actuators");
  if (*s.actuator_armed < 0) return make_result(check::kArmedState, Verdict::Skip, "no HIL_ACTUATOR_CONTROLS received yet");
  const bool act = *s.actuator_armed == 1;
  const std::string saw = std::string("HIL_ACTUATOR_CONTROLS ") + (act ? "armed" : "disarmed") + ", HEARTBEAT " +
                          (heartbeat->armed() ? "armed" : "disarmed");
  if (act == heartbeat->armed()) return make_result(check::kArmedState, Verdict::Pass, saw);
  return make_result(check::kArmedState, Verdict::Fail, saw + ": the HIL stream and the autopilot disagree",
                     "the HIL instance may belong to another PX4 or an earlier boot: " + std::string(kRestartPx4));
}

}  // namespace hitl::doctor
