// The IMU samples of a recording: each HIL_SENSOR whose fields_updated carries accel and gyro, from
// the system that sent the first one (the simulator, in a `hitl sim --record` tlog; a board's or a
// client's HIL_SENSOR from another system is left out), in FRD as sent. For `hitl inspect --allan`.
// Bounded: at most `max_samples` are kept (six doubles each); the rest of the file is counted, not
// kept. A window [from_s, to_s] of HIL_SENSOR's time_usec (the simulated time, s) keeps only the
// samples in it. imu_allan(): the Allan deviation of each axis (allan_deviation.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/telemetry/allan_deviation.h"

namespace hitl::telemetry {

/// 2^20 samples: ~70 minutes at 250 Hz, 48 MiB of samples (plus one 8 MiB working copy per curve).
inline constexpr std::size_t kMaxImuSeriesSamples = std::size_t{1} << 20;

struct ImuSeries {
  std::array<std::vector<double>, 3> gyro_FRD_rad_s;  ///< x, y, z
  std::array<std::vector<double>, 3> accel_FRD_m_s2;
  double rate_hz = 0.0;      ///< (samples - 1) / (last time_usec - first), of the kept samples
  double duration_s = 0.0;   ///< first to last kept sample, by time_usec
  std::size_t samples = 0;   ///< kept
  std::uint64_t samples_beyond_cap = 0;  ///< IMU samples after the cap, not kept
  std::uint64_t other_systems = 0;       ///< HIL_SENSOR from another system, left out
  std::size_t gaps = 0;      ///< intervals over 1.5x the mean (a pause or a lost sample)
};

/// The part of a recording read: HIL_SENSOR time_usec * 1e-6 within [from_s, to_s].
struct ImuWindow {
  double from_s = 0.0;
  double to_s = std::numeric_limits<double>::infinity();
  bool whole() const { return from_s <= 0.0 && to_s == std::numeric_limits<double>::infinity(); }
};

/// Reads `path` (a regular file or a pipe). Errors name the file: not a tlog, no IMU HIL_SENSOR
/// (in the window), fewer than kAllanMinSamples samples, time that does not move forward.
Expected<ImuSeries> read_imu_series(const std::string& path, std::size_t max_samples = kMaxImuSeriesSamples,
                                    const ImuWindow& window = {});


/// One axis of one sensor's Allan deviation.
struct AxisAllan {
  const char* sensor;  ///< "gyro", "accel"
  const char* axis;    ///< "x", "y", "z" (FRD)
  const char* unit;    ///< "rad/s", "m/s^2"
  std::vector<AllanPoint> curve;
  AllanFit fit;
};

/// The six curves of a series (gyro x, y, z, then accel x, y, z) and their fits.
std::vector<AxisAllan> imu_allan(const ImuSeries& series);

}  // namespace hitl::telemetry
