// hitl inspect --tlog FILE --spectrum: the amplitude spectrum of a recording's IMU
// (engine/telemetry/imu_spectrum.h), its strongest peaks per sensor and axis, printed as text or,
// with --json, as one object with the (decimated) curves.
#pragma once

#include <string>

#include "cli/common_options.h"
#include "engine/telemetry/imu_series.h"

namespace hitl::cli {

/// Points of each curve in --json at most (consecutive bins grouped, each group's largest shown).
inline constexpr std::size_t kSpectrumJsonPoints = 512;

/// Reads `tlog` within `window`, prints the spectra's peaks (and, with --json, the curves); returns
/// the exit code (2: the file is refused).
int run_inspect_spectrum(const GlobalOptions& global, const std::string& tlog, const telemetry::ImuWindow& window);

}  // namespace hitl::cli
