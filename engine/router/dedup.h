// Drops a frame seen again within a short window: the same bytes arriving on two paths (the board
// on USB-Ethernet and Wi-Fi, two routers in a chain), as mavlink-router's de-duplication does.
// Keyed on a 64-bit hash of the whole frame (header with seq, payload, CRC), so a sender's genuine
// repeat (a new seq) is never taken for a duplicate.
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <unordered_set>

namespace hitl::router {

class DedupWindow {
 public:
  /// window_s <= 0: off (nothing is a duplicate).
  explicit DedupWindow(double window_s) : window_s_(window_s) {}

  /// True when these bytes were seen within the window (the caller drops them); remembers them.
  bool seen_recently(std::span<const uint8_t> frame, double now_s);
  std::size_t size() const { return keys_.size(); }

 private:
  struct Entry {
    uint64_t key;
    double time_s;
  };
  double window_s_;
  std::deque<Entry> order_;
  std::unordered_multiset<uint64_t> keys_;
};

}  // namespace hitl::router
