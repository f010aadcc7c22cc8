// A short, adaptive busy-poll of sockets before blocking on them, for lockstep: when the other end
// answers within tens of microseconds (hitl target, PX4 SITL on the same host, each on its own
// core), polling without blocking for that long saves the sleep and the cross-core wake-up every
// step would otherwise pay. Bounded both ways: a spin lasts at most kMaxBudget_s (4 times the mean
// of the spins that found something, at least kMinBudget_s); a spin that finds nothing (a slow
// peer, or one sharing this core on a loaded machine) doubles the number of waits that skip
// spinning (up to kMaxBackoff), and a wait that saw nothing at all skips kMaxBackoff, so a slow or
// idle peer costs one short spin in every kMaxBackoff waits.
#pragma once

#include <poll.h>

#include <cstdint>
#include <span>

namespace hitl::net {

class AdaptiveBusyPoll {
 public:
  static constexpr double kMaxBudget_s = 100e-6;
  static constexpr double kMinBudget_s = 20e-6;
  static constexpr uint32_t kMaxBackoff = 1024;

  /// Polls `fds` (POLLIN) without blocking until one is readable or the budget runs out; true when
  /// one is. While backing off it returns false at once, without a system call.
  bool spin(std::span<pollfd> fds);
  /// A blocking wait ran out with nothing: back off fully.
  void on_nothing();
  double budget_s() const { return budget_s_; }
  uint64_t spins_tried() const { return tried_; }
  uint64_t spins_answered() const { return answered_; }

 private:
  double mean_s_ = kMaxBudget_s / 4;  ///< running mean of the successful spins' lengths (1/8 to the newest)
  double budget_s_ = kMaxBudget_s;
  uint32_t backoff_ = 0;  ///< waits to skip after the next failed spin / 2
  uint32_t skip_ = 0;     ///< waits left to skip
  uint64_t tried_ = 0, answered_ = 0;
};

}  // namespace hitl::net
