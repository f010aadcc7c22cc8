// One live stream seen by its arrival (or send) times: the rate over the last window, the
// jitter of its intervals (their standard deviation within the window), the longest gap, and how
// long ago the last one was. Windows are closed by the owner, about once a second, so the figures
// follow what the stream does now rather than since the start.
#pragma once

#include <cstdint>

namespace hitl::telemetry {

struct StreamStats {
  uint64_t count = 0;         ///< since the start
  double rate_hz = 0;         ///< over the last closed window
  double jitter_ms = 0;       ///< standard deviation of the intervals in the last closed window
  double max_gap_ms = 0;      ///< longest interval in the last closed window
  double since_last_s = -1;   ///< time since the last arrival; -1 before the first
};

class StreamMeter {
 public:
  /// One arrival at `t_s` (a monotonic clock, seconds).
  void arrival(double t_s);
  /// Closes the window at `now_s` and opens the next.
  void roll(double now_s);
  /// The last closed window's figures, with `since_last_s` at `now_s`.
  StreamStats stats(double now_s) const;

 private:
  uint64_t count_ = 0;
  double last_s_ = -1;
  double window_start_s_ = -1;
  // the open window: arrivals and Welford's running mean and M2 of the intervals
  uint64_t window_arrivals_ = 0;
  uint64_t window_gaps_ = 0;
  double gap_mean_s_ = 0;
  double gap_m2_s2_ = 0;
  double gap_max_s_ = 0;
  StreamStats closed_;
};

}  // namespace hitl::telemetry
