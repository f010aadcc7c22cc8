#include "engine/net/busy_poll.h"

#include <algorithm>

#include "base/common/clock.h"

namespace hitl::net {

bool AdaptiveBusyPoll::spin(std::span<pollfd> fds) {
  if (skip_ > 0) {
    --skip_;
    return false;
  }
  ++tried_;
  const double start_s = monotonic_s();
  double now_s = start_s;
  do {
    if (::poll(fds.data(), fds.size(), 0) > 0) {
      ++answered_;
      backoff_ = 0;
      mean_s_ += (monotonic_s() - start_s - mean_s_) / 8.0;
      budget_s_ = std::clamp(4.0 * mean_s_, kMinBudget_s, kMaxBudget_s);
      return true;
    }
    now_s = monotonic_s();
  } while (now_s - start_s < budget_s_);
  backoff_ = std::min(kMaxBackoff, backoff_ == 0 ? 1 : 2 * backoff_);
  skip_ = backoff_;
  return false;
}

void AdaptiveBusyPoll::on_nothing() {
  backoff_ = kMaxBackoff;
  skip_ = kMaxBackoff;
}

}  // namespace hitl::net
