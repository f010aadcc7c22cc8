#include "engine/telemetry/amplitude_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <unsupported/Eigen/FFT>

namespace hitl::telemetry {

AmplitudeSpectrum welch_amplitude_spectrum(std::span<const double> samples, double rate_hz, std::size_t segment_samples,
                                           std::size_t max_peaks) {
  AmplitudeSpectrum out;
  const std::size_t n = segment_samples;
  if (n < 8 || !(rate_hz > 0.0) || samples.size() < n) return out;
  out.segment_samples = n;
  out.resolution_hz = rate_hz / static_cast<double>(n);
  std::vector<double> window(n);
  double window_sum = 0.0, window_sum2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    // Periodic Hann (the DFT-even one): its main lobe spans +-2 bins exactly.
    window[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n));
    window_sum += window[i];
    window_sum2 += window[i] * window[i];
  }
  const std::size_t bins = n / 2 + 1;
  std::vector<double> power(bins, 0.0);
  Eigen::FFT<double> fft;
  std::vector<double> segment(n);
  std::vector<std::complex<double>> spectrum;
  const std::size_t hop = n / 2;
  for (std::size_t start = 0; start + n <= samples.size(); start += hop) {
    double mean = 0.0;
    for (std::size_t i = 0; i < n; ++i) mean += samples[start + i];
    mean /= static_cast<double>(n);
    for (std::size_t i = 0; i < n; ++i) segment[i] = (samples[start + i] - mean) * window[i];
    fft.fwd(spectrum, segment);
    for (std::size_t k = 0; k < bins; ++k) power[k] += std::norm(spectrum[k]);
    ++out.segments;
  }
  for (double& p : power) p /= static_cast<double>(out.segments);
  out.curve.resize(bins);
  for (std::size_t k = 0; k < bins; ++k)
    out.curve[k] = {static_cast<double>(k) * out.resolution_hz, 2.0 * std::sqrt(power[k]) / window_sum};

  for (std::size_t k = 1; k < bins; ++k) {
    // The largest within its main lobe (+-2 bins): a noise bump on a line's flank is not a peak.
    bool largest = power[k] > 0.0 && power[k] > power[k - 1];
    for (std::size_t j = k >= 2 ? k - 2 : 0; largest && j <= std::min(k + 2, bins - 1); ++j)
      if (j != k && (j < k ? power[j] >= power[k] : power[j] > power[k])) largest = false;
    if (!largest) continue;
    double offset_bins = 0.0;
    if (k + 1 < bins && power[k - 1] > 0.0 && power[k + 1] > 0.0) {
      const double a = std::log(power[k - 1]), b = std::log(power[k]), c = std::log(power[k + 1]);
      const double denominator = a - 2.0 * b + c;
      if (denominator < 0.0) offset_bins = std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
    }
    double lobe = 0.0;
    for (std::size_t j = k >= 2 ? k - 2 : 0; j <= std::min(k + 2, bins - 1); ++j) lobe += power[j];
    out.peaks.push_back({(static_cast<double>(k) + offset_bins) * out.resolution_hz,
                         2.0 * std::sqrt(lobe / (static_cast<double>(n) * window_sum2))});
  }
  std::sort(out.peaks.begin(), out.peaks.end(), [](const SpectrumPoint& a, const SpectrumPoint& b) { return a.amplitude > b.amplitude; });
  if (out.peaks.size() > max_peaks) out.peaks.resize(max_peaks);
  return out;
}

std::vector<SpectrumPoint> decimate_spectrum(std::span<const SpectrumPoint> curve, std::size_t max_points) {
  if (max_points == 0) return {};
  if (curve.size() <= max_points) return {curve.begin(), curve.end()};
  const std::size_t group = (curve.size() + max_points - 1) / max_points;
  std::vector<SpectrumPoint> out;
  for (std::size_t start = 0; start < curve.size(); start += group) {
    const auto end = curve.begin() + static_cast<std::ptrdiff_t>(std::min(start + group, curve.size()));
    out.push_back(*std::max_element(curve.begin() + static_cast<std::ptrdiff_t>(start), end,
                                    [](const SpectrumPoint& a, const SpectrumPoint& b) { return a.amplitude < b.amplitude; }));
  }
  return out;
}

}  // namespace hitl::telemetry
