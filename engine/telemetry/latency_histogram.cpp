#include "engine/telemetry/latency_histogram.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace hitl::telemetry {
namespace {

constexpr uint64_t kSub = uint64_t{1} << LatencyHistogram::kSubBits;

// Values below kSub us have a bin each; above, each power of two is split into kSub bins.
std::size_t fine_bin_of(uint64_t v_us) {
  if (v_us < kSub) return static_cast<std::size_t>(v_us);
  const int msb = 63 - std::countl_zero(v_us);
  const int shift = msb - LatencyHistogram::kSubBits;
  const std::size_t octave = static_cast<std::size_t>(shift) + 1;
  const std::size_t sub = static_cast<std::size_t>((v_us >> shift) & (kSub - 1));
  return std::min(LatencyHistogram::kFineBins - 1, octave * kSub + sub);
}

// The middle of a fine bin, in us.
double fine_bin_value(std::size_t b) {
  if (b < kSub) return static_cast<double>(b) + 0.5;
  const std::size_t octave = b / kSub;
  const std::size_t sub = b % kSub;
  const double width = std::ldexp(1.0, static_cast<int>(octave) - 1);
  const double base = width * static_cast<double>(kSub);
  return base + (static_cast<double>(sub) + 0.5) * width;
}

}  // namespace

void LatencyHistogram::add(double latency_us) {
  const double v = std::isfinite(latency_us) ? std::max(0.0, latency_us) : 0.0;
  if (count_ == 0 || v < min_us_) min_us_ = v;
  if (count_ == 0 || v > max_us_) max_us_ = v;
  ++count_;
  sum_us_ += v;
  const uint64_t whole_us = v >= 1.8e19 ? UINT64_MAX : static_cast<uint64_t>(v);
  ++fine_[fine_bin_of(whole_us)];
  const auto edge = std::upper_bound(kLatencyBinEdges_us.begin(), kLatencyBinEdges_us.end(), whole_us);
  ++coarse_[static_cast<std::size_t>(edge - kLatencyBinEdges_us.begin())];
}

double LatencyHistogram::percentile(double q) const {
  if (count_ == 0) return 0;
  const auto rank = std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(count_))));
  uint64_t seen = 0;
  for (std::size_t b = 0; b < fine_.size(); ++b) {
    seen += fine_[b];
    if (seen >= rank) return std::clamp(fine_bin_value(b), min_us_, max_us_);
  }
  return max_us_;
}

LatencySummary LatencyHistogram::summary() const {
  LatencySummary s;
  s.count = count_;
  for (std::size_t i = 0; i < s.bins.size(); ++i) {
    s.bins[i].lo_us = i == 0 ? 0 : kLatencyBinEdges_us[i - 1];
    s.bins[i].hi_us = i < kLatencyBinEdges_us.size() ? kLatencyBinEdges_us[i] : 0;
    s.bins[i].count = coarse_[i];
  }
  if (count_ == 0) return s;
  s.min_us = min_us_;
  s.mean_us = sum_us_ / static_cast<double>(count_);
  s.p50_us = percentile(0.50);
  s.p95_us = percentile(0.95);
  s.p99_us = percentile(0.99);
  s.max_us = max_us_;
  return s;
}

}  // namespace hitl::telemetry
