// The messages panel's lines, written from any thread (session events, the autopilot's
// STATUSTEXT, action outcomes, shell output) and copied whole by the drawing thread. Keeps the
// newest kCapacity lines; stamps each with seconds since the log was made, or with the clock it is
// given (the sim dashboard: simulated time, the header's clock).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "tui/dashboard_model.h"

namespace hitl::tui {

/// STATUSTEXT's MAV_SEVERITY (0 emergency .. 7 debug) as the panel's four grades.
Severity severity_from_mavlink(uint8_t mav_severity);

class MessageLog {
 public:
  static constexpr std::size_t kCapacity = 500;
  MessageLog();
  void add(Severity severity, const std::string& text);
  /// Several lines (shell output): one entry per line, blank lines dropped.
  void add_lines(Severity severity, const std::string& text);
  std::vector<LogLine> lines() const;
  /// Stamps later lines with `clock_s()` (seconds) instead of the time since the log was made.
  void set_clock(std::function<double()> clock_s);

 private:
  mutable std::mutex mutex_;
  std::deque<LogLine> lines_;
  double start_s_;
  std::function<double()> clock_s_;
};

}  // namespace hitl::tui
