// What the session sent and received, per message id: counts, and rates over the status window.
// Sends the kernel refused are never counted as sent: they are send_errors, with the latest
// refusal in words (docs/sim.md "Output").
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace hitl::hil {

struct StreamCounter {
  uint64_t count = 0;
  uint64_t window = 0;  ///< since the last roll()
  double rate_hz = 0;   ///< over the last window
};

struct Traffic {
  std::map<uint32_t, StreamCounter> sent;
  std::map<uint32_t, StreamCounter> received;
  uint64_t send_errors = 0;
  std::string last_send_error;

  void count_sent(uint32_t id, uint64_t n) {
    auto& c = sent[id];
    c.count += n;
    c.window += n;
  }
  void count_received(uint32_t id) {
    auto& c = received[id];
    ++c.count;
    ++c.window;
  }
  void count_failed(uint64_t n, const std::string& why) {
    send_errors += n;
    last_send_error = why;
  }
  uint64_t delivered() const {
    uint64_t n = 0;
    for (const auto& [id, c] : sent) n += c.count;
    return n;
  }
  /// Turns the window's counts into rates over `window_s` of wall time.
  void roll(double window_s) {
    for (auto* m : {&sent, &received})
      for (auto& [id, c] : *m) {
        c.rate_hz = static_cast<double>(c.window) / window_s;
        c.window = 0;
      }
  }
};

}  // namespace hitl::hil
