// The report's Allan deviation plots (docs/report.md "Allan deviation"): the IMU's overlapping Allan
// deviation (engine/telemetry/allan_deviation.h) over the recording's longest stretch at rest, one
// log-log plot per sensor (gyro, accel) with a curve per axis, and marked on it the white noise
// N/sqrt(tau) and the bias instability's floor 0.664 B: fitted to this recording, and the IMU's own
// figures when the simulator said them at the start (engine/telemetry/imu_noise_statement.h).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "engine/report/flight_log.h"
#include "engine/report/plots.h"

namespace hitl::report {

/// At rest: the simulator's truth moving slower than this and turning slower than kRestRate_deg_s.
inline constexpr double kRestSpeed_m_s = 0.05;
inline constexpr double kRestRate_deg_s = 1.0;
/// The shortest rest stretch drawn (its curve reaches tau = a tenth of it).
inline constexpr double kMinRest_s = 30.0;
/// The most IMU samples a curve is computed over (the first of a longer stretch): 2^20, ~70 min at 250 Hz.
inline constexpr std::size_t kMaxAllanSamples = std::size_t{1} << 20;

/// A stretch of the IMU track: samples [first, last).
struct RestStretch {
  std::size_t first = 0, last = 0;
  std::size_t size() const { return last - first; }
};

/// The longest stretch of IMU samples at rest by the truth (nullopt: no truth, or none of kMinRest_s).
std::optional<RestStretch> longest_rest(const FlightLog& log);

/// The two plots ("allan-gyro", "allan-accel"), log_axes set; without a rest stretch, both without
/// series (their `sources` say what is needed; plots_of leaves them out: a flight without a long
/// rest lacks nothing).
std::vector<Plot> allan_plots(const FlightLog& log);

}  // namespace hitl::report
