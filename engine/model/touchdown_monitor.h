// Counts touchdowns and measures how each one went, from the model's state after every step:
// what the landing checks (tests, the session's summary) read. A touchdown is the lowest contact
// point reaching the ground after it was more than kAirborne_m above it; the rebound is the
// highest that point rises in the kReboundWindow_s after a touchdown (a hop or a bounce; a takeoff
// that soon counts too); the peak is the largest specific force in the kPeakWindow_s after it.
#pragma once

#include <cstdint>

#include "engine/model/vehicle_state.h"

namespace hitl::model {

struct TouchdownStats {
  uint64_t touchdowns = 0;
  double max_rebound_m = 0.0;           ///< over all touchdowns
  double max_touchdown_speed_m_s = 0.0; ///< vertical speed at the moment of touching
  double peak_accel_m_s2 = 0.0;         ///< largest specific force (norm) just after a touchdown
  double last_touchdown_s = -1.0;       ///< simulated time of the last one (-1: none)
};

class TouchdownMonitor {
 public:
  static constexpr double kAirborne_m = 0.02;
  static constexpr double kReboundWindow_s = 2.0;
  static constexpr double kPeakWindow_s = 0.5;

  /// Feeds the state after a step.
  void observe(const VehicleState& state);
  /// The vehicle was put back (at rest on the ground): no touchdown, no rebound.
  void on_reset();
  const TouchdownStats& stats() const { return stats_; }

 private:
  bool airborne_ = false;
  bool started_ = false;
  TouchdownStats stats_;
};

}  // namespace hitl::model
