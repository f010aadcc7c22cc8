// Every `hitl doctor` check, in the order it runs and reports: the spec's Troubleshooting list and
// Verification phases (docs/doctor.md says what each looks at and why). The ids are the JSON's
// `check` and what tests refer to; this is the one place they are spelled.
#pragma once

#include <string>
#include <vector>

#include "engine/doctor/check_result.h"

namespace hitl::doctor {

namespace group {
inline constexpr const char* kHost = "host";
inline constexpr const char* kLink = "link";
inline constexpr const char* kSensors = "board sensors";
inline constexpr const char* kParameters = "parameters";
inline constexpr const char* kEstimator = "estimator";
inline constexpr const char* kArming = "arming";
inline constexpr const char* kVio = "VIO";
inline constexpr const char* kSimulator = "simulator";
inline constexpr const char* kPx4 = "PX4 SITL";
}  // namespace group

namespace check {
// host
inline constexpr const char* kRoute = "route";
inline constexpr const char* kAdb = "adb";
inline constexpr const char* kPorts = "ports";
// link
inline constexpr const char* kHeartbeat = "heartbeat";
inline constexpr const char* kHilMode = "hil-mode";
inline constexpr const char* kMavlinkInstances = "mavlink-instances";
inline constexpr const char* kActuators = "actuators";
inline constexpr const char* kActuatorFlags = "actuator-flags";
inline constexpr const char* kArmedState = "armed-state";
// board sensors
inline constexpr const char* kDspHitl = "dsp-hitl";
// parameters
inline constexpr const char* kParamsSystem = "params-system";
inline constexpr const char* kParamsCalibration = "params-calibration";
inline constexpr const char* kParamsEkf2 = "params-ekf2";
inline constexpr const char* kParamsArming = "params-arming";
inline constexpr const char* kParamsAllocation = "params-allocation";
// estimator, arming
inline constexpr const char* kEstimator = "estimator";
inline constexpr const char* kArming = "arming";
// VIO
inline constexpr const char* kVioOdometry = "vio-odometry";
inline constexpr const char* kVioServer = "vio-server";
inline constexpr const char* kVioPipe = "vio-pipe";
inline constexpr const char* kVisionHub = "vision-hub";
// simulator
inline constexpr const char* kSession = "session";
inline constexpr const char* kPaused = "paused";
inline constexpr const char* kRealTime = "real-time";
inline constexpr const char* kLateTicks = "late-ticks";
inline constexpr const char* kLoopLatency = "loop-latency";
// PX4 SITL (hitl sim --px4, hitl doctor --px4 DIR)
inline constexpr const char* kPx4Build = "px4-build";
inline constexpr const char* kPx4Instance = "px4-instance";
inline constexpr const char* kPx4Connected = "px4-connected";
inline constexpr const char* kPx4Params = "px4-params";
}  // namespace check

struct CheckInfo {
  const char* id;
  const char* group;
  const char* title;  ///< what the human output shows: "HEARTBEAT from the board"
};

/// All checks in order.
const std::vector<CheckInfo>& doctor_checks();
/// The entry of `id` (an id of doctor_checks()).
const CheckInfo& check_info(const std::string& id);

/// A result of check `id` with its group filled in.
CheckResult make_result(const char* id, Verdict verdict, std::string saw, std::string fix = "");

}  // namespace hitl::doctor
