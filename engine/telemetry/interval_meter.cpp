#include "engine/telemetry/interval_meter.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace hitl::telemetry {
namespace {

// Histogram of gaps in units of 1/16 us: values below 256 have a bucket each; above, each
// power of two is split into 256 buckets. 40 octaves cover gaps up to ~19 hours.
constexpr int kSubBits = 8;
constexpr uint64_t kSub = 1U << kSubBits;
constexpr std::size_t kOctaves = 40;
constexpr std::size_t kBuckets = kSub + kOctaves * kSub;

std::size_t bucket_of(uint64_t v) {
  if (v < kSub) return static_cast<std::size_t>(v);
  const int msb = 63 - std::countl_zero(v);
  const int shift = msb - kSubBits;
  const std::size_t octave = static_cast<std::size_t>(msb - kSubBits);
  const std::size_t sub = static_cast<std::size_t>((v >> shift) & (kSub - 1));
  return std::min(kBuckets - 1, kSub + octave * kSub + sub);
}

// Midpoint of a bucket, in the same 1/16 us units.
double bucket_value(std::size_t b) {
  if (b < kSub) return static_cast<double>(b);
  const std::size_t octave = (b - kSub) / kSub;
  const std::size_t sub = (b - kSub) % kSub;
  const double base = std::ldexp(1.0, static_cast<int>(octave + kSubBits));
  const double width = base / static_cast<double>(kSub);
  return base + (static_cast<double>(sub) + 0.5) * width;
}

}  // namespace

void IntervalMeter::arrival(int64_t t_ns) {
  ++arrivals_;
  if (++segment_arrivals_ == 1) {
    if (arrivals_ == 1) first_ns_ = t_ns;
    segment_first_ns_ = last_ns_ = t_ns;
    return;
  }
  if (t_ns < last_ns_) return;
  // Unsigned: any two int64 times (a log's clock can jump by centuries) give a gap without overflow.
  const uint64_t gap_ns = static_cast<uint64_t>(t_ns) - static_cast<uint64_t>(last_ns_);
  last_ns_ = t_ns;
  const double gap_us = static_cast<double>(gap_ns) / 1000.0;
  ++gaps_;
  const double delta = gap_us - mean_;
  mean_ += delta / static_cast<double>(gaps_);
  m2_ += delta * (gap_us - mean_);
  if (gaps_ == 1) min_ = max_ = gap_us;
  min_ = std::min(min_, gap_us);
  max_ = std::max(max_, gap_us);
  count_bucket(bucket_of(gap_ns / 1000 * 16 + gap_ns % 1000 * 16 / 1000));
}

void IntervalMeter::end_segment(int64_t end_ns) {
  if (segment_arrivals_ == 0) return;
  closed_intervals_ += segment_arrivals_ - 1;
  closed_span_ns_ += static_cast<double>(std::max(end_ns, last_ns_)) - static_cast<double>(segment_first_ns_);
  segment_arrivals_ = 0;
}

double IntervalMeter::rate_hz(int64_t now_ns) const {
  double intervals = static_cast<double>(closed_intervals_), span_ns = closed_span_ns_;
  if (segment_arrivals_ > 0) {
    intervals += static_cast<double>(segment_arrivals_ - 1);
    span_ns += static_cast<double>(std::max(now_ns, last_ns_)) - static_cast<double>(segment_first_ns_);
  }
  return intervals >= 1 && span_ns > 0 ? intervals / (span_ns * 1e-9) : 0.0;
}

void IntervalMeter::count_bucket(std::size_t b) {
  if (histogram_.empty()) {
    lowest_bucket_ = b;
  } else if (b < lowest_bucket_) {
    histogram_.insert(histogram_.begin(), lowest_bucket_ - b, 0);
    lowest_bucket_ = b;
  }
  if (b - lowest_bucket_ >= histogram_.size()) histogram_.resize(b - lowest_bucket_ + 1, 0);
  ++histogram_[b - lowest_bucket_];
}

double IntervalMeter::percentile(double q) const {
  if (gaps_ == 0) return 0;
  const auto rank = static_cast<uint64_t>(std::ceil(q * static_cast<double>(gaps_)));
  uint64_t seen = 0;
  for (std::size_t b = 0; b < histogram_.size(); ++b) {
    seen += histogram_[b];
    if (seen >= std::max<uint64_t>(rank, 1)) return std::clamp(bucket_value(lowest_bucket_ + b) / 16.0, min_, max_);
  }
  return max_;
}

GapSummary IntervalMeter::summary() const {
  GapSummary s;
  s.count = gaps_;
  if (gaps_ == 0) return s;
  s.mean_us = mean_;
  s.std_us = gaps_ > 1 ? std::sqrt(m2_ / static_cast<double>(gaps_ - 1)) : 0.0;
  s.min_us = min_;
  s.max_us = max_;
  s.p50_us = percentile(0.50);
  s.p99_us = percentile(0.99);
  return s;
}

}  // namespace hitl::telemetry
