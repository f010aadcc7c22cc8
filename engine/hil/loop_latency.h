// Loop latency at the board: for each HIL_SENSOR sent (one per tick with an IMU sample), the wall
// time until the HIL_ACTUATOR_CONTROLS that answers it arrives. In lockstep the answer is matched
// by step: the one whose time_usec echoes the HIL_SENSOR's (PX4 SITL and `hitl target --lockstep`
// stamp it so); an answer on the board's own clock (a PX4 board in HIL mode) answers, as outside
// lockstep, every HIL_SENSOR still waiting: from its send to the next actuator message.
//
// Bounded: at most kMaxPending HIL_SENSORs wait for an answer (1 s at 250 Hz); older ones are
// counted as unanswered. The distribution is a telemetry::LatencyHistogram (fixed bins).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

#include "engine/hil/actuator_input.h"
#include "engine/telemetry/latency_histogram.h"

namespace hitl::hil {

struct LoopLatencySummary {
  telemetry::LatencySummary latency;  ///< wall time, HIL_SENSOR sent -> its answer received, us
  uint64_t sensors = 0;               ///< HIL_SENSORs that expected an answer
  uint64_t unanswered = 0;            ///< never answered (held longer than kMaxPending sensors, or still waiting at the end)
  bool lockstep = false;              ///< matched by step (time_usec echo)
};

class LoopLatency {
 public:
  static constexpr std::size_t kMaxPending = 250;

  explicit LoopLatency(bool lockstep) : lockstep_(lockstep) {}
  /// A HIL_SENSOR with this time_usec left (or was queued to leave) at `wall_s` (monotonic).
  void on_hil_sensor_sent(uint64_t time_usec, double wall_s);
  /// A HIL_ACTUATOR_CONTROLS stamped `time_usec` arrived at `wall_s` (monotonic).
  void on_actuator(uint64_t time_usec, double wall_s);
  LoopLatencySummary summary() const;

 private:
  struct Pending {
    uint64_t time_usec;
    double sent_wall_s;
  };
  bool lockstep_;
  std::deque<Pending> pending_;
  telemetry::LatencyHistogram histogram_;
  uint64_t sensors_ = 0;
  uint64_t dropped_ = 0;
};

}  // namespace hitl::hil
