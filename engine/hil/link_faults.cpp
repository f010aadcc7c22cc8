#include "engine/hil/link_faults.h"

#include <utility>

#include "engine/model/random_stream.h"

namespace hitl::hil {

LinkFaults::LinkFaults(uint64_t seed) : rng_(model::stream_seed(seed, "hil-drop")) {}

void LinkFaults::set(double drop_p, double delay_s) {
  drop_p_ = drop_p;
  delay_s_ = delay_s;
}

void LinkFaults::hold(std::span<const uint8_t> frame, std::optional<uint32_t> counted_id) {
  open_.frames.emplace_back(frame.begin(), frame.end());
  if (counted_id) ++open_.counts[*counted_id];
}

void LinkFaults::close_datagram(double now_s) {
  if (open_.frames.empty()) return;
  Datagram d = std::exchange(open_, {});
  // One draw per held datagram, also at p = 0 (under hil-delay alone): the sequence depends on the seed and the steps only.
  const bool drop = uniform_(rng_) < drop_p_;
  if (drop) {
    ++dropped_;
    return;
  }
  if (delay_s_ > 0) ++delayed_;
  d.due_s = now_s + delay_s_;
  // Never before an earlier datagram (the delay shrank): order is kept.
  if (!queue_.empty() && d.due_s < queue_.back().due_s) d.due_s = queue_.back().due_s;
  queue_.push_back(std::move(d));
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
