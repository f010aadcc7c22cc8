// The overlapping Allan deviation of a sensor's output at rest (IEEE Std 952 / 1554), and what is
// read from it:
//   avar(tau = m/rate) = 1 / (2 (n - 2m + 1)) * sum_k (a_{k+m} - a_k)^2,   a_k the mean of samples
//   k .. k+m-1 (every start k: "overlapping"); adev = sqrt(avar)
// at cluster sizes m = 1 and then ~10 per decade up to n / 10 (at least 10 independent clusters).
//   noise_density     white noise N [unit/sqrt(Hz)]: the tau = 1 s value of a line of slope -1/2
//                     (N / sqrt(tau)) fitted, in logs, to the points before the minimum that are at
//                     least 3x the minimum (where a floor or a walk adds at most ~6 %)
//   bias_instability  B [unit]: the curve's minimum / 0.664 (flicker noise's floor, IEEE 952)
// Pure functions: no I/O.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace hitl::telemetry {

struct AllanPoint {
  double tau_s = 0.0;
  double deviation = 0.0;  ///< in the samples' unit
  std::size_t cluster_samples = 0;  ///< m
};

struct AllanFit {
  double noise_density = 0.0;     ///< unit/sqrt(Hz)
  double bias_instability = 0.0;  ///< unit
  double minimum_tau_s = 0.0;     ///< where the curve's minimum lies
  std::size_t fit_points = 0;     ///< points in the -1/2 fit
};

/// The smallest number of samples the curve needs (three cluster sizes).
inline constexpr std::size_t kAllanMinSamples = 40;

/// The curve of `samples` taken at `rate_hz` (empty below kAllanMinSamples or a rate <= 0).
std::vector<AllanPoint> overlapping_allan_deviation(std::span<const double> samples, double rate_hz);

/// noise_density and bias_instability read from a curve (all zero for an empty one).
AllanFit fit_allan(std::span<const AllanPoint> curve);

}  // namespace hitl::telemetry
