// The messages panel's lines, written from any thread (session events, the autopilot's
// STATUSTEXT, action outcomes, shell output) and copied whole by the drawing thread. Keeps the
// newest kCapacity lines; stamps each with seconds since the log was made, or with the clock it is
// given (the sim dashboard: simulated time, the header's clock). The autopilot's STATUSTEXT shows
// once: the same text from the same source again within kRepeatWindow_s (wall clock) of its last
// showing moves that line to the bottom with a count, "(x3)", instead of adding another.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "tui/dashboard_model.h"

namespace hitl::tui {

/// STATUSTEXT's MAV_SEVERITY (0 emergency .. 7 debug) as the panel's four grades.
Severity severity_from_mavlink(uint8_t mav_severity);

class MessageLog {
 public:
  static constexpr std::size_t kCapacity = 500;
  static constexpr double kRepeatWindow_s = 10.0;
  /// `wall_s`: the clock the repeat window is measured on (tests give their own).
  explicit MessageLog(std::function<double()> wall_s = {});
  void add(Severity severity, const std::string& text);
  /// A STATUSTEXT from `source` (who sent it): repeats within the window are collapsed.
  void add_statustext(Severity severity, const std::string& source, const std::string& text);
  /// The outcome of a key (a refusal, an ACK, a pause): a line, also kept as the last outcome.
  void add_outcome(Severity severity, const std::string& text);
  /// The last key's outcome, for the header; nullopt before any.
  std::optional<LogLine> outcome() const;
  /// Several lines (shell output): one entry per line, blank lines dropped.
  void add_lines(Severity severity, const std::string& text);
  std::vector<LogLine> lines() const;
  /// Stamps later lines with `clock_s()` (seconds) instead of the time since the log was made.
  void set_clock(std::function<double()> clock_s);

 private:
  struct Entry {
    LogLine line;
    std::string repeat_key;  ///< source and text of a STATUSTEXT; empty for the rest
    double wall_s = 0;       ///< when it was last shown
  };
  void push(Entry entry);

  mutable std::mutex mutex_;
  std::deque<Entry> entries_;
  std::function<double()> wall_s_;
  double start_s_;
  std::function<double()> clock_s_;
  std::optional<LogLine> outcome_;
};

}  // namespace hitl::tui
