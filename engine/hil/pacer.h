// Paces the session loop on absolute deadlines (clock_nanosleep TIMER_ABSTIME on
// CLOCK_MONOTONIC), so the rate never drifts: tick k is due at start + k * period / speed.
// A tick that starts more than one period after its deadline is late: it is counted and the loop
// catches up by running the following ticks back to back. After a long stall (more than
// kMaxCatchUp behind) the schedule is re-anchored instead of bursting, and that is counted too.
// With a spin (--spin-us) it sleeps until that long before the deadline and then reads the clock
// until the deadline: the wake-up's lateness is taken out of the tick's start, at the cost of the
// spin's CPU time (docs/sim.md "Timing at the board").
#pragma once

#include <atomic>
#include <cstdint>
#include <ctime>

namespace hitl::hil {

struct PacerStats {
  uint64_t ticks = 0;
  uint64_t late = 0;       ///< ticks that began more than one period after their deadline
  uint64_t resyncs = 0;    ///< stalls longer than the catch-up window: schedule re-anchored
  double max_lateness_s = 0;
};

/// Sleeps until `t_s` on the monotonic clock (base/common/clock.h's monotonic_s), absolute.
void sleep_until_monotonic_s(double t_s);

class Pacer {
 public:
  static constexpr double kMaxCatchUp_s = 0.1;
  static constexpr double kMaxSlice_s = 0.05;

  static constexpr double kMaxSpin_s = 0.002;

  /// `speed` is the real-time factor to hold (1 = real time); 0 = no pacing, as fast as possible.
  /// `spin_s` (0 .. kMaxSpin_s): the last part of each wait spent spinning on the clock.
  Pacer(double period_s, double speed, double spin_s = 0.0);
  void start();
  /// Sleeps until the next tick is due (returns at once when behind, and within kMaxSlice_s once
  /// `stop` is set).
  void wait_next(const std::atomic<bool>* stop = nullptr);
  const PacerStats& stats() const { return stats_; }
  /// When wait_next() will return, monotonic seconds (0 when not paced: at once).
  double next_due_s() const;

 private:
  double wall_period_s_;
  bool paced_;
  double spin_s_;
  timespec anchor_{};
  uint64_t k_ = 0;  ///< ticks since the anchor
  PacerStats stats_;
};

}  // namespace hitl::hil
