#include "engine/model/touchdown_monitor.h"

#include <algorithm>

namespace hitl::model {

void TouchdownMonitor::observe(const VehicleState& state) {
  const double clearance_m = state.ground_clearance_m;
  if (!started_) {
    started_ = true;
    airborne_ = clearance_m > kAirborne_m;
  }
  if (airborne_ && clearance_m <= 0.0) {
    airborne_ = false;
    ++stats_.touchdowns;
    stats_.last_touchdown_s = state.time_s;
    stats_.max_touchdown_speed_m_s = std::max(stats_.max_touchdown_speed_m_s, -state.v_ENU_m_s.z());
  } else if (!airborne_ && clearance_m > kAirborne_m) {
    airborne_ = true;
  }
  if (stats_.last_touchdown_s < 0.0) return;
  const double since_s = state.time_s - stats_.last_touchdown_s;
  if (since_s <= kReboundWindow_s) stats_.max_rebound_m = std::max(stats_.max_rebound_m, clearance_m);
  if (since_s <= kPeakWindow_s)
    stats_.peak_accel_m_s2 = std::max(stats_.peak_accel_m_s2, state.specific_force_FLU_m_s2.norm());
}

void TouchdownMonitor::on_reset() {
  airborne_ = false;
  started_ = true;
  stats_.last_touchdown_s = -1.0;
}

}  // namespace hitl::model
