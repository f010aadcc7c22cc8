// The rolling history behind the dashboard's graphs: a fixed ring per series (window_s x
// sample_hz samples), fed from each frame's model, sampled at most sample_hz times a second on the
// caller's clock, so memory stays bounded however long the session runs.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tui/dashboard_model.h"

namespace hitl::tui {

/// The last `capacity` values pushed, oldest first.
class SampleRing {
 public:
  explicit SampleRing(std::size_t capacity) : capacity_(capacity) { values_.reserve(capacity); }
  void push(double value);
  std::vector<double> values() const;
  std::size_t size() const { return values_.size(); }

 private:
  std::size_t capacity_;
  std::vector<double> values_;
  std::size_t next_ = 0;  ///< where the next value goes once full
};

class GraphHistory {
 public:
  /// At most this many data paths are graphed (the spec's table has fewer).
  static constexpr std::size_t kMaxRateSeries = 16;

  explicit GraphHistory(double window_s = 60, double sample_hz = 10);
  /// Takes a sample of `model` (altitudes, the data paths' rates) and of `tracking_error_m` for
  /// each sample period `now_s` has moved on (the dashboard's clock is the session's simulated
  /// time: nothing while paused, several periods a frame faster than real time); the first call,
  /// and one after the clock went back, takes one.
  void add(double now_s, const DashboardModel& model, std::optional<double> tracking_error_m);
  GraphsPanel panel() const;

 private:
  void push_sample(const DashboardModel& m, std::optional<double> tracking_error_m);

  struct Rate {
    std::string name;
    double expected_hz = 0;
    SampleRing samples;
  };
  double window_s_;
  double period_s_;
  std::size_t capacity_;
  double last_s_ = -1;
  SampleRing truth_, estimate_, tracking_;
  std::vector<Rate> rates_;
};

}  // namespace hitl::tui
