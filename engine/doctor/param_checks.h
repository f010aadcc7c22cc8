// The parameters (everything `hitl params check` checks, engine/vehicle/params_check.h), one check
// per category of the spec's "HITL Default Parameters". Pure.
#pragma once

#include <vector>

#include "base/common/expected.h"
#include "engine/doctor/check_result.h"
#include "engine/vehicle/params_check.h"

namespace hitl::doctor {

/// params-system, params-calibration, params-ekf2, params-arming, params-allocation, in order, from
/// the board's download (or why there is none).
std::vector<CheckResult> param_checks(const Expected<std::vector<vehicle::Param>>& board);

}  // namespace hitl::doctor
