#include "engine/hil/loop_latency.h"

#include <algorithm>

namespace hitl::hil {

void LoopLatency::on_hil_sensor_sent(uint64_t time_usec, double wall_s) {
  ++sensors_;
  if (pending_.size() >= kMaxPending) {
    pending_.pop_front();
    ++dropped_;
  }
  pending_.push_back({time_usec, wall_s});
}

void LoopLatency::on_actuator(uint64_t time_usec, double wall_s) {
  if (pending_.empty()) return;  // no HIL_SENSOR waits: a second answer, or the stream before the first
  auto answered_end = pending_.end();  // outside lockstep (or no echo): every one waiting is answered
  if (lockstep_) {
    auto it = std::find_if(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.time_usec == time_usec; });
    if (it != pending_.end()) {
      histogram_.add((wall_s - it->sent_wall_s) * 1e6);
      ++it;
      dropped_ += static_cast<uint64_t>(it - pending_.begin()) - 1;  // earlier ones were skipped by the board
      pending_.erase(pending_.begin(), it);
      return;
    }
    const bool echoes_older = time_usec < pending_.front().time_usec &&
                              pending_.front().time_usec - time_usec <= ActuatorInput::kEchoWindow_us;
    if (echoes_older) return;  // a late answer to a HIL_SENSOR already answered
  }
  for (auto it = pending_.begin(); it != answered_end; ++it) histogram_.add((wall_s - it->sent_wall_s) * 1e6);
  pending_.clear();
}

LoopLatencySummary LoopLatency::summary() const {
  LoopLatencySummary s;
  s.latency = histogram_.summary();
  s.sensors = sensors_;
  s.unanswered = dropped_ + pending_.size();
  s.lockstep = lockstep_;
  return s;
}

}  // namespace hitl::hil
