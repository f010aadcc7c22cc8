#include "engine/telemetry/allan_deviation.h"

#include <algorithm>
#include <cmath>

namespace hitl::telemetry {
namespace {

/// m = 1, then ~10 per decade (each distinct), up to n / 10.
std::vector<std::size_t> cluster_sizes(std::size_t n) {
  std::vector<std::size_t> out;
  const std::size_t max_m = n / 10;
  for (int i = 0;; ++i) {
    const auto m = static_cast<std::size_t>(std::llround(std::pow(10.0, i / 10.0)));
    if (m > max_m) break;
    if (out.empty() || m != out.back()) out.push_back(m);
  }
  return out;
}

}  // namespace

std::vector<AllanPoint> overlapping_allan_deviation(std::span<const double> samples, double rate_hz) {
  std::vector<AllanPoint> curve;
  const std::size_t n = samples.size();
  if (n < kAllanMinSamples || !(rate_hz > 0.0)) return curve;
  // Prefix sums of the samples less their mean (small numbers: a constant such as gravity on an
  // accelerometer's z does not eat the differences' precision).
  double mean = 0.0;
  for (double x : samples) mean += x;
  mean /= static_cast<double>(n);
  std::vector<double> prefix(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + (samples[i] - mean);
  for (std::size_t m : cluster_sizes(n)) {
    const std::size_t terms = n - 2 * m + 1;
    double sum = 0.0;
    for (std::size_t k = 0; k < terms; ++k) {
      // a_{k+m} - a_k, times m
      const double d = (prefix[k + 2 * m] - prefix[k + m]) - (prefix[k + m] - prefix[k]);
      sum += d * d;
    }
    const double md = static_cast<double>(m);
    const double avar = sum / (md * md) / (2.0 * static_cast<double>(terms));
    curve.push_back({md / rate_hz, std::sqrt(avar), m});
  }
  return curve;
}

AllanFit fit_allan(std::span<const AllanPoint> curve) {
  AllanFit fit;
  if (curve.empty()) return fit;
  const auto lowest = std::min_element(curve.begin(), curve.end(),
                                       [](const AllanPoint& a, const AllanPoint& b) { return a.deviation < b.deviation; });
  fit.bias_instability = lowest->deviation / 0.664;
  fit.minimum_tau_s = lowest->tau_s;
  // log N = mean over the fit's points of (log adev + 1/2 log tau): the -1/2 line through them. The
  // points: before the minimum, at least 3x its value (a floor or a walk adds at most ~6 % there);
  // the first point when none is.
  double sum_log = 0.0;
  for (auto p = curve.begin(); p != lowest; ++p) {
    if (p->deviation < 3.0 * lowest->deviation) continue;
    sum_log += std::log(p->deviation) + 0.5 * std::log(p->tau_s);
    ++fit.fit_points;
  }
  if (fit.fit_points == 0 && curve.front().deviation > 0.0) {
    sum_log = std::log(curve.front().deviation) + 0.5 * std::log(curve.front().tau_s);
    fit.fit_points = 1;
  }
  if (fit.fit_points > 0) fit.noise_density = std::exp(sum_log / static_cast<double>(fit.fit_points));
  return fit;
}

}  // namespace hitl::telemetry
