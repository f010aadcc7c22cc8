#include "engine/telemetry/imu_spectrum.h"

#include <algorithm>
#include <cmath>

namespace hitl::telemetry {

std::size_t spectrum_segment_samples(const ImuSeries& series) {
  return std::max<std::size_t>(8, static_cast<std::size_t>(std::lround(series.rate_hz * kSpectrumSegment_s)));
}

std::vector<AxisSpectrum> imu_spectrum(const ImuSeries& series) {
  std::vector<AxisSpectrum> out;
  static constexpr const char* kAxes[3] = {"x", "y", "z"};
  const std::size_t n = spectrum_segment_samples(series);
  for (int i = 0; i < 3; ++i)
    out.push_back({"gyro", kAxes[i], "rad/s", welch_amplitude_spectrum(series.gyro_FRD_rad_s[i], series.rate_hz, n, kSpectrumPeaks)});
  for (int i = 0; i < 3; ++i)
    out.push_back({"accel", kAxes[i], "m/s^2", welch_amplitude_spectrum(series.accel_FRD_m_s2[i], series.rate_hz, n, kSpectrumPeaks)});
  return out;
}

}  // namespace hitl::telemetry
