// A link's faults (docs/faults.md), the same on the HIL link (hil-*) and the VIO link (vio-*):
// drop with a probability, burst loss (Gilbert-Elliott), a rate limit (token bucket), delay and
// jitter, reorder (a datagram swaps places with the next), duplicate. Seeded from --seed, each
// link its own stream; every datagram draws the same number of times, so the sequence depends on
// the seed and the steps only. While any is on (or something is still held), the link gives its
// frames here instead of to the socket; a step's frames close into one datagram, which is dropped
// or queued with a due time, and the session releases what is due between its ticks (never waiting
// for it: the 250 Hz loop keeps its pace). Delay and jitter keep the order; only reorder changes it.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <string_view>
#include <vector>

#include "engine/faults/fault_schedule.h"

namespace hitl::hil {

/// What a link's faults did, since the session started.
struct LinkFaultCounts {
  uint64_t dropped = 0;     ///< drop, burst and rate together
  uint64_t delayed = 0;
  uint64_t reordered = 0;
  uint64_t duplicated = 0;
};

class LinkFaults {
 public:
  struct Datagram {
    double due_s = 0;                          ///< monotonic
    std::vector<std::vector<uint8_t>> frames;
    std::map<uint32_t, uint64_t> counts;       ///< messages by id, counted as sent when it leaves
  };

  /// `stream`: the link's own random stream ("hil-drop", "vio-link").
  LinkFaults(uint64_t seed, std::string_view stream);
  /// What the active faults do now (from the fault schedule, every step), at the step's simulated
  /// time: the rate limit counts simulated seconds (as the board's clock does in lockstep), so what
  /// it drops depends on the steps, not on how fast they run.
  void set(const faults::LinkImpairment& impairment, double sim_s) {
    p_ = impairment;
    sim_s_ = sim_s;
  }
  /// True while frames must go through here: a fault is on, or datagrams are still held.
  bool holding() const { return p_.any() || !queue_.empty() || !open_.frames.empty() || held_back_; }
  void hold(std::span<const uint8_t> frame, std::optional<uint32_t> counted_id);
  /// Closes the step's datagram: dropped, or due at now + delay + jitter (held back one under reorder);
  /// `now_s` is monotonic (the delays are wall time), the rate limit's time the step's (set()).
  void close_datagram(double now_s);
  /// Hands every datagram due by `now_s` to `send`, oldest first.
  void release_due(double now_s, const std::function<void(Datagram&)>& send);
  std::optional<double> next_due_s() const;

  const LinkFaultCounts& counts() const { return counts_; }
  uint64_t dropped_datagrams() const { return counts_.dropped; }
  uint64_t delayed_datagrams() const { return counts_.delayed; }

 private:
  void enqueue(Datagram d);

  faults::LinkImpairment p_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  Datagram open_;
  std::deque<Datagram> queue_;
  std::optional<Datagram> held_back_;  ///< reorder: goes after the next datagram
  bool bad_ = false;                   ///< Gilbert-Elliott's state
  double tokens_ = 1;                  ///< the rate limit's bucket (one datagram deep)
  double sim_s_ = 0;                   ///< the step's simulated time (set())
  std::optional<double> last_close_sim_s_;
  LinkFaultCounts counts_;
};

}  // namespace hitl::hil
