// A period with an absolute next-due time, driven by a clock the caller passes in (no sleeping,
// no threads). Ticks stay on the grid anchor + k * period, so the rate does not drift with the
// caller's polling jitter. A caller more than one period late gets one tick, not a burst: the grid
// is then re-anchored at that moment and the resync is counted.
#pragma once

#include <cstdint>

namespace hitl::target {

class PeriodicSchedule {
 public:
  explicit PeriodicSchedule(uint64_t period_us) : period_us_(period_us > 0 ? period_us : 1) {}

  /// Starts (or restarts) the grid: the first tick is due at `now_us`.
  void start(uint64_t now_us) {
    next_due_us_ = now_us;
    running_ = true;
  }
  void stop() { running_ = false; }
  bool running() const { return running_; }

  /// True when running and a tick is due at `now_us`. Does not consume it.
  bool due(uint64_t now_us) const { return running_ && now_us >= next_due_us_; }

  /// Consumes the tick due at `now_us` (call only when due()).
  void consume(uint64_t now_us) {
    next_due_us_ += period_us_;
    if (next_due_us_ <= now_us) {  // more than a period behind: re-anchor instead of bursting
      next_due_us_ = now_us + period_us_;
      ++resyncs_;
    }
  }

  uint64_t period_us() const { return period_us_; }
  /// The next tick's due time (meaningful while running).
  uint64_t next_due_us() const { return next_due_us_; }
  /// How often the grid was re-anchored because the caller was late by more than a period.
  uint64_t resyncs() const { return resyncs_; }

 private:
  uint64_t period_us_;
  uint64_t next_due_us_ = 0;
  uint64_t resyncs_ = 0;
  bool running_ = false;
};

}  // namespace hitl::target
