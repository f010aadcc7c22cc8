#include "engine/hil/link_faults.h"

#include <algorithm>
#include <utility>

#include "engine/model/random_stream.h"

namespace hitl::hil {

LinkFaults::LinkFaults(uint64_t seed, std::string_view stream) : rng_(model::stream_seed(seed, stream)) {}

void LinkFaults::hold(std::span<const uint8_t> frame, std::optional<uint32_t> counted_id) {
  open_.frames.emplace_back(frame.begin(), frame.end());
  if (counted_id) ++open_.counts[*counted_id];
}

void LinkFaults::enqueue(Datagram d) {
  // Never before an earlier datagram (the delay shrank, jitter): order is kept.
  if (!queue_.empty() && d.due_s < queue_.back().due_s) d.due_s = queue_.back().due_s;
  queue_.push_back(std::move(d));
}

void LinkFaults::close_datagram(double now_s) {
  if (open_.frames.empty()) return;
  Datagram d = std::exchange(open_, {});
  // The same draws for every datagram, whichever faults are on.
  const double u_drop = uniform_(rng_), u_burst = uniform_(rng_), u_jitter = uniform_(rng_), u_reorder = uniform_(rng_),
               u_duplicate = uniform_(rng_);
  // Gilbert-Elliott: the channel moves between good and bad first; a datagram sent while bad is lost.
  bad_ = p_.burst_bad_p > 0 && (bad_ ? !(u_burst < p_.burst_good_p) : u_burst < p_.burst_bad_p);
  // The rate limit: a bucket one datagram deep, filled at max_rate_hz over simulated time.
  if (last_close_sim_s_) tokens_ = std::min(1.0, tokens_ + (sim_s_ - *last_close_sim_s_) * p_.max_rate_hz);
  last_close_sim_s_ = sim_s_;
  const bool over_rate = p_.max_rate_hz > 0 && tokens_ < 1.0 - 1e-9;
  if (u_drop < p_.drop_p || bad_ || over_rate) {
    ++counts_.dropped;
    return;
  }
  if (p_.max_rate_hz > 0) tokens_ -= 1.0;
  const double delay_s = p_.delay_s + u_jitter * p_.jitter_s;
  if (delay_s > 0) ++counts_.delayed;
  d.due_s = now_s + delay_s;
  const bool duplicate = u_duplicate < p_.duplicate_p;
  if (held_back_) {  // the one held back goes after this one
    Datagram later = std::exchange(*held_back_, {});
    held_back_.reset();
    later.due_s = d.due_s;
    enqueue(d);
    enqueue(std::move(later));
    ++counts_.reordered;
  } else if (u_reorder < p_.reorder_p) {
    held_back_ = d;
  } else {
    enqueue(d);
  }
  if (duplicate) {
    Datagram copy = d;
    copy.counts.clear();  // counted once, as sent (the copy is the link's doing)
    enqueue(std::move(copy));
    ++counts_.duplicated;
  }
}

void LinkFaults::release_due(double now_s, const std::function<void(Datagram&)>& send) {
  while (!queue_.empty() && queue_.front().due_s <= now_s) {
    Datagram d = std::move(queue_.front());
    queue_.pop_front();
    send(d);
  }
}

std::optional<double> LinkFaults::next_due_s() const {
  if (queue_.empty()) return std::nullopt;
  return queue_.front().due_s;
}

}  // namespace hitl::hil
