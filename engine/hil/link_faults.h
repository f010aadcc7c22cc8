// The HIL link's faults (docs/faults.md): hil-drop drops each datagram to the flight stack with a
// probability (seeded from --seed), hil-delay holds each back until a due time. While either is on
// (or something is still held), StackLink gives its frames here instead of to the link; a step's
// frames close into one datagram at flush, which is dropped or queued, and the session releases
// what is due between its ticks (never waiting for it: the 250 Hz loop keeps its pace). Order is
// kept: a datagram never overtakes an earlier one.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <vector>

namespace hitl::hil {

class LinkFaults {
 public:
  struct Datagram {
    double due_s = 0;                          ///< monotonic
    std::vector<std::vector<uint8_t>> frames;
    std::map<uint32_t, uint64_t> counts;       ///< messages by id, counted as sent when it leaves
  };

  explicit LinkFaults(uint64_t seed);
  /// The active hil-drop probability and hil-delay (from the fault schedule, every step).
  void set(double drop_p, double delay_s);
  /// True while frames must go through here: a fault is on, or datagrams are still held.
  bool holding() const { return drop_p_ > 0 || delay_s_ > 0 || !queue_.empty() || !open_.frames.empty(); }
  void hold(std::span<const uint8_t> frame, std::optional<uint32_t> counted_id);
  /// Closes the step's datagram: dropped with the probability, else due at now + delay.
  void close_datagram(double now_s);
  /// Hands every datagram due by `now_s` to `send`, oldest first.
  void release_due(double now_s, const std::function<void(Datagram&)>& send);
  std::optional<double> next_due_s() const;

  uint64_t dropped_datagrams() const { return dropped_; }
  uint64_t delayed_datagrams() const { return delayed_; }

 private:
  double drop_p_ = 0;
  double delay_s_ = 0;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  Datagram open_;
  std::deque<Datagram> queue_;
  uint64_t dropped_ = 0;
  uint64_t delayed_ = 0;
};

}  // namespace hitl::hil
