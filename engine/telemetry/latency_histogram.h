// A latency distribution in fixed memory: percentiles from a log-linear histogram (16 bins per
// octave of microseconds: within ~3 % of the true value, clamped to the exact min and max), and a
// coarse histogram over fixed edges for people (the JSON summary, the dashboard). Nothing grows
// with the number of samples: a session of hours costs the same few kilobytes as one of seconds.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace hitl::telemetry {

/// The coarse bins' upper edges, in microseconds; a last bin holds everything above the last edge.
inline constexpr std::array<uint64_t, 11> kLatencyBinEdges_us = {250,   500,   1000,  2000,   4000,  8000,
                                                                 16000, 32000, 64000, 128000, 256000};

struct LatencyBin {
  uint64_t lo_us = 0;
  uint64_t hi_us = 0;  ///< 0: no upper edge (the last bin)
  uint64_t count = 0;
};

struct LatencySummary {
  uint64_t count = 0;
  double min_us = 0;
  double mean_us = 0;
  double p50_us = 0;
  double p95_us = 0;
  double p99_us = 0;
  double max_us = 0;
  std::array<LatencyBin, kLatencyBinEdges_us.size() + 1> bins{};  ///< over kLatencyBinEdges_us
};

class LatencyHistogram {
 public:
  /// One latency, in microseconds (negative is taken as 0).
  void add(double latency_us);
  /// The value below which a fraction `q` (0..1) of the samples lie; 0 with no samples.
  double percentile(double q) const;
  LatencySummary summary() const;
  uint64_t count() const { return count_; }

  static constexpr int kSubBits = 4;                    ///< 16 bins per octave
  static constexpr std::size_t kOctaves = 32;           ///< above 16 us: up to 2^36 us (~19 hours); beyond: the last bin
  static constexpr std::size_t kFineBins = (kOctaves + 1) << kSubBits;

 private:
  std::array<uint64_t, kFineBins> fine_{};
  std::array<uint64_t, kLatencyBinEdges_us.size() + 1> coarse_{};
  uint64_t count_ = 0;
  double sum_us_ = 0;
  double min_us_ = 0;
  double max_us_ = 0;
};

}  // namespace hitl::telemetry
