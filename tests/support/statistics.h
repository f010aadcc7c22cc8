// Small statistics for tests that check noise against its configured density.
#pragma once

#include <cmath>
#include <vector>

namespace hitl::test {

/// Sample standard deviation (n - 1).
inline double sample_sigma(const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double var = 0.0;
  for (double v : x) var += (v - mean) * (v - mean);
  return std::sqrt(var / static_cast<double>(x.size() - 1));
}

}  // namespace hitl::test
