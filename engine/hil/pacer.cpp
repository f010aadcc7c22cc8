#include "engine/hil/pacer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace hitl::hil {
namespace {

timespec add_s(timespec t, double s) {
  const auto ns = static_cast<int64_t>(std::llround(s * 1e9));
  int64_t total = static_cast<int64_t>(t.tv_nsec) + ns % 1000000000;
  t.tv_sec += static_cast<time_t>(ns / 1000000000 + total / 1000000000);
  t.tv_nsec = static_cast<long>(total % 1000000000);
  if (t.tv_nsec < 0) {
    t.tv_nsec += 1000000000;
    t.tv_sec -= 1;
  }
  return t;
}

double to_s(const timespec& t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9; }

}  // namespace

void sleep_until_monotonic_s(double t_s) {
  timespec due{};
  due.tv_sec = static_cast<time_t>(t_s);
  due.tv_nsec = static_cast<long>((t_s - static_cast<double>(due.tv_sec)) * 1e9);
  if (due.tv_nsec >= 1000000000) due.tv_nsec = 999999999;
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, nullptr) == EINTR) {
  }
}

double Pacer::next_due_s() const {
  if (!paced_) return 0.0;
  return to_s(add_s(anchor_, static_cast<double>(k_ + 1) * wall_period_s_));
}

Pacer::Pacer(double period_s, double speed, double spin_s)
    : wall_period_s_(speed > 0 ? period_s / speed : 0.0),
      paced_(speed > 0),
      spin_s_(std::clamp(spin_s, 0.0, std::min(kMaxSpin_s, wall_period_s_))) {}

void Pacer::start() {
  clock_gettime(CLOCK_MONOTONIC, &anchor_);
  k_ = 0;
}

void Pacer::wait_next(const std::atomic<bool>* stop) {
  ++stats_.ticks;
  if (!paced_) return;
  ++k_;
  const timespec due = add_s(anchor_, static_cast<double>(k_) * wall_period_s_);
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  const double lateness_s = to_s(now) - to_s(due);
  if (lateness_s > wall_period_s_) {
    ++stats_.late;
    stats_.max_lateness_s = std::max(stats_.max_lateness_s, lateness_s);
    if (lateness_s > kMaxCatchUp_s) {
      ++stats_.resyncs;
      clock_gettime(CLOCK_MONOTONIC, &anchor_);
      k_ = 0;
    }
    return;
  }
  // Sleep in slices of at most kMaxSlice_s so that a stop (Ctrl-C, q) is seen within one slice
  // even at a slow --speed, where one step can be seconds of wall time; with a spin, only until
  // spin_s_ before the deadline.
  const timespec wake = add_s(due, -spin_s_);
  for (;;) {
    if (stop != nullptr && stop->load()) return;
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (to_s(now) >= to_s(wake)) break;
    timespec slice = add_s(now, kMaxSlice_s);
    if (to_s(slice) > to_s(wake)) slice = wake;
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &slice, nullptr);
  }
  while (to_s(now) < to_s(due)) clock_gettime(CLOCK_MONOTONIC, &now);  // the spin (none when spin_s_ is 0)
}

}  // namespace hitl::hil
