#include "engine/telemetry/stream_meter.h"

#include <algorithm>
#include <cmath>

namespace hitl::telemetry {

void StreamMeter::arrival(double t_s) {
  if (window_start_s_ < 0) window_start_s_ = t_s;
  if (last_s_ >= 0 && t_s >= last_s_) {  // a clock that stepped back is not an interval
    const double gap_s = t_s - last_s_;
    ++window_gaps_;
    const double delta = gap_s - gap_mean_s_;
    gap_mean_s_ += delta / static_cast<double>(window_gaps_);
    gap_m2_s2_ += delta * (gap_s - gap_mean_s_);
    gap_max_s_ = std::max(gap_max_s_, gap_s);
  }
  last_s_ = t_s;
  ++count_;
  ++window_arrivals_;
}

void StreamMeter::roll(double now_s) {
  if (window_start_s_ < 0) window_start_s_ = now_s;
  const double window_s = now_s - window_start_s_;
  closed_.count = count_;
  closed_.rate_hz = window_s > 0 ? static_cast<double>(window_arrivals_) / window_s : 0.0;
  closed_.jitter_ms = window_gaps_ >= 2 ? std::sqrt(gap_m2_s2_ / static_cast<double>(window_gaps_ - 1)) * 1000.0 : 0.0;
  closed_.max_gap_ms = gap_max_s_ * 1000.0;
  window_start_s_ = now_s;
  window_arrivals_ = 0;
  window_gaps_ = 0;
  gap_mean_s_ = 0;
  gap_m2_s2_ = 0;
  gap_max_s_ = 0;
}

StreamStats StreamMeter::stats(double now_s) const {
  StreamStats s = closed_;
  s.count = count_;
  s.since_last_s = last_s_ < 0 ? -1.0 : std::max(0.0, now_s - last_s_);
  return s;
}

}  // namespace hitl::telemetry
