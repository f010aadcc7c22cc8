// The operator's pause (the dashboard): the session's monotonic clock without the time spent
// paused, on which actuator timeouts are measured.
#pragma once

namespace hitl::hil {

class PauseClock {
 public:
  bool paused() const { return paused_; }
  void pause(double wall_s) {
    paused_ = true;
    pause_start_s_ = wall_s;
  }
  void resume(double wall_s) {
    paused_total_s_ += wall_s - pause_start_s_;
    paused_ = false;
  }
  /// `wall_s` minus the wall time spent paused so far.
  double unpaused_s(double wall_s) const {
    return wall_s - paused_total_s_ - (paused_ ? wall_s - pause_start_s_ : 0.0);
  }

 private:
  bool paused_ = false;
  double pause_start_s_ = 0;
  double paused_total_s_ = 0;
};

}  // namespace hitl::hil
