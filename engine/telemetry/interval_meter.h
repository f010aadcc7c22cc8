// Inter-arrival statistics of one stream: count, mean/std (Welford), min/max, and
// percentiles from a log-linear histogram (256 buckets per octave: ~0.4 % resolution).
// The histogram holds only the span of buckets the gaps have used (empty until the second
// arrival, ~1 KB for a steady stream), so a meter per message id stays cheap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hitl::telemetry {

struct GapSummary {
  uint64_t count = 0;  ///< gaps measured (arrivals - 1)
  double mean_us = 0;
  double std_us = 0;
  double min_us = 0;
  double max_us = 0;
  double p50_us = 0;
  double p99_us = 0;
};

class IntervalMeter {
 public:
  /// Records an arrival at `t_ns`; the first arrival only starts the clock. Arrivals that go back
  /// in time (clock steps) are not counted as gaps.
  void arrival(int64_t t_ns);
  /// Ends the current segment of the stream at `end_ns` (a log's stretch, tlog_timeline.h): the next
  /// arrival starts a new one, with no gap measured across the two.
  void end_segment(int64_t end_ns);
  /// (arrivals - 1) per second, over the segments so far, each from its first arrival to its end
  /// (the current one to `now_ns`): 0 before two arrivals in one segment.
  double rate_hz(int64_t now_ns) const;
  GapSummary summary() const;
  int64_t first_ns() const { return first_ns_; }
  int64_t last_ns() const { return last_ns_; }
  uint64_t arrivals() const { return arrivals_; }
  /// Memory the histogram holds (its cost per stream).
  std::size_t histogram_bytes() const { return histogram_.capacity() * sizeof(uint32_t); }

 private:
  void count_bucket(std::size_t bucket);
  double percentile(double q) const;

  uint64_t arrivals_ = 0;
  uint64_t segment_arrivals_ = 0;
  int64_t segment_first_ns_ = 0;
  uint64_t closed_intervals_ = 0;  ///< arrivals - 1 of each segment ended
  double closed_span_ns_ = 0;      ///< first arrival to end of each segment ended
  int64_t first_ns_ = 0;
  int64_t last_ns_ = 0;
  uint64_t gaps_ = 0;
  double mean_ = 0;
  double m2_ = 0;
  double min_ = 0;
  double max_ = 0;
  std::size_t lowest_bucket_ = 0;    ///< the bucket histogram_[0] counts
  std::vector<uint32_t> histogram_;  ///< buckets lowest_bucket_ .. the highest used
};

}  // namespace hitl::telemetry
