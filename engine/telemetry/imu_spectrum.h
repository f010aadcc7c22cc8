// The amplitude spectrum of each axis of a recording's IMU (imu_series.h, amplitude_spectrum.h):
// for `hitl inspect --spectrum`. Segments of one second at the IMU's rate (the rate rounded to whole
// samples: 250 at 250 Hz, a 1 Hz resolution), overlapping by half.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/telemetry/amplitude_spectrum.h"
#include "engine/telemetry/imu_series.h"

namespace hitl::telemetry {

inline constexpr double kSpectrumSegment_s = 1.0;
inline constexpr std::size_t kSpectrumPeaks = 5;  ///< peaks kept per axis

/// One axis of one sensor's spectrum.
struct AxisSpectrum {
  const char* sensor;  ///< "gyro", "accel"
  const char* axis;    ///< "x", "y", "z" (FRD)
  const char* unit;    ///< "rad/s", "m/s^2"
  AmplitudeSpectrum spectrum;
};

/// Samples in one segment of `series` (kSpectrumSegment_s at its rate, at least 8).
std::size_t spectrum_segment_samples(const ImuSeries& series);

/// The six spectra of a series (gyro x, y, z, then accel x, y, z); each empty (no curve) when the
/// series is shorter than one segment.
std::vector<AxisSpectrum> imu_spectrum(const ImuSeries& series);

}  // namespace hitl::telemetry
