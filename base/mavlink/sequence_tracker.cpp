#include "base/mavlink/sequence_tracker.h"

namespace hitl::mavlink {

void SequenceTracker::observe(uint8_t seq) {
  ++stats_.received;
  if (!started_) {
    started_ = true;
    expected_ = static_cast<uint8_t>(seq + 1);
    return;
  }
  const uint8_t gap = static_cast<uint8_t>(seq - expected_);
  if (gap < 128) {
    stats_.lost += gap;
    expected_ = static_cast<uint8_t>(seq + 1);
  } else {
    ++stats_.out_of_order;
  }
}

}  // namespace hitl::mavlink
