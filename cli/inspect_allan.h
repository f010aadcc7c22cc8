// hitl inspect --tlog FILE --allan: the Allan deviation of a recording's IMU at rest
// (engine/telemetry/imu_series.h), printed as text or, with --json, as one object.
#pragma once

#include <string>

#include "cli/common_options.h"
#include "engine/telemetry/imu_series.h"

namespace hitl::cli {

/// Reads `tlog` within `window`, prints the curves and their fits; returns the exit code (2: the file is refused).
int run_inspect_allan(const GlobalOptions& global, const std::string& tlog, const telemetry::ImuWindow& window = {});

}  // namespace hitl::cli
