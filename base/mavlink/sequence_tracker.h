// Per-source sequence accounting: MAVLink senders number their frames 0..255 per link,
// so a jump in seq from one (sysid, compid) is frames lost on the way.
#pragma once

#include <cstdint>

namespace hitl::mavlink {

struct SequenceStats {
  uint64_t received = 0;
  uint64_t lost = 0;          ///< frames skipped in the sequence
  uint64_t out_of_order = 0;  ///< frames older than the last one (duplicates, reordering, sender restart)

  /// Lost as a fraction of received + lost.
  double loss_ratio() const { return received + lost == 0 ? 0.0 : static_cast<double>(lost) / static_cast<double>(received + lost); }
};

/// Tracks one sender. A forward jump of 1..127 counts the skipped frames as lost; a jump of
/// 128 or more is read as an older frame (duplicate or reordering), as 8-bit sequences wrap.
class SequenceTracker {
 public:
  void observe(uint8_t seq);
  /// The next frame starts the sequence again (a joined log's next part): no loss counted across.
  void restart() { started_ = false; }
  const SequenceStats& stats() const { return stats_; }

 private:
  SequenceStats stats_;
  bool started_ = false;
  uint8_t expected_ = 0;
};

}  // namespace hitl::mavlink
