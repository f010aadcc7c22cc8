// The estimator and arming (spec Troubleshooting "Vehicle does not arm": "Check EKF2 is fusing:
// listener estimator_status", "Check commander status for preflight check failures"). Pure.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/doctor/check_result.h"
#include "engine/doctor/observations.h"

namespace hitl::doctor {

/// Test ratios above this warn (1 is EKF2's gate: above it the measurement is rejected).
inline constexpr double kTestRatioWarn = 0.5;

/// estimator: ESTIMATOR_STATUS has attitude, horizontal and vertical velocity and absolute
/// position, no fault bit (GPS glitch, accel error, constant position mode), test ratios below 1.
CheckResult estimator_check(const std::optional<EstimatorStatusSeen>& status);

/// "Preflight Fail: ..." lines of STATUSTEXT and of `commander check`, oldest first, each once.
std::vector<std::string> preflight_failures(const std::vector<std::string>& statustext, const std::string& commander_check);

/// arming: armed already, or SYS_STATUS's prearm check healthy; otherwise the board's reasons in
/// words (`commander_check` is that command's output, or why there is none) and the failing
/// sensors SYS_STATUS names.
CheckResult arming_check(const std::optional<HeartbeatSeen>& heartbeat, const std::optional<SysStatusSeen>& sys_status,
                         const std::vector<std::string>& statustext, const Expected<std::string>& commander_check);

}  // namespace hitl::doctor
