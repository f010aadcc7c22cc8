#include "engine/report/spectrum.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>

namespace hitl::report {

AmplitudeSpectrum amplitude_spectrum(const std::vector<double>& samples, double rate_hz, std::size_t segment) {
  AmplitudeSpectrum out;
  if (segment < 2 || samples.size() < segment || !(rate_hz > 0)) return out;
  std::vector<double> window(segment);
  double window_sum = 0;
  for (std::size_t i = 0; i < segment; ++i) {
    window[i] = 0.5 - 0.5 * std::cos(2 * M_PI * static_cast<double>(i) / static_cast<double>(segment));
    window_sum += window[i];
  }
  const std::size_t bins = segment / 2 + 1;
  std::vector<double> power(bins, 0.0);
  Eigen::FFT<double> fft;
  std::vector<double> x(segment);
  std::vector<std::complex<double>> X;
  for (std::size_t start = 0; start + segment <= samples.size(); start += segment / 2) {
    double mean = 0;
    for (std::size_t i = 0; i < segment; ++i) mean += samples[start + i];
    mean /= static_cast<double>(segment);
    for (std::size_t i = 0; i < segment; ++i) {
      const double v = samples[start + i] - mean;
      x[i] = std::isfinite(v) ? v * window[i] : 0.0;  // a damaged sample is no vibration
    }
    fft.fwd(X, x);
    for (std::size_t k = 0; k < bins; ++k) power[k] += std::norm(X[k]);
    ++out.segments;
  }
  for (std::size_t k = 0; k < bins; ++k) {
    out.freq_hz.push_back(static_cast<double>(k) * rate_hz / static_cast<double>(segment));
    out.amplitude.push_back(2.0 * std::sqrt(power[k] / static_cast<double>(out.segments)) / window_sum);
  }
  return out;
}

double sample_rate_hz(const std::vector<double>& t_s) {
  if (t_s.size() < 2) return 0;
  std::vector<double> dt;
  dt.reserve(t_s.size() - 1);
  for (std::size_t i = 1; i < t_s.size(); ++i) dt.push_back(t_s[i] - t_s[i - 1]);
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  const double median_s = dt[dt.size() / 2];
  return median_s > 0 ? 1.0 / median_s : 0;
}

}  // namespace hitl::report
