#include "engine/router/dedup.h"

namespace hitl::router {
namespace {

/// FNV-1a, 64 bit: fast and plenty for telling frames apart within a second.
uint64_t hash_of(std::span<const uint8_t> bytes) {
  uint64_t h = 1469598103934665603ull;
  for (uint8_t b : bytes) {
    h ^= b;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

bool DedupWindow::seen_recently(std::span<const uint8_t> frame, double now_s) {
  if (window_s_ <= 0) return false;
  while (!order_.empty() && now_s - order_.front().time_s > window_s_) {
    keys_.erase(keys_.find(order_.front().key));
    order_.pop_front();
  }
  const uint64_t key = hash_of(frame);
  if (keys_.count(key) != 0) return true;
  keys_.insert(key);
  order_.push_back({key, now_s});
  return false;
}

}  // namespace hitl::router
