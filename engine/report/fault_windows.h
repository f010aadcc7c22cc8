// The simulator's faults in a recording: each window from its start to its end, read from the
// STATUSTEXT the simulator sends when one starts or ends (engine/faults FaultChange::text():
// "t=20.000 s fault imu-vibration:8,90 started (5 s)", "t=25.000 s fault imu-vibration:8,90 ended"),
// with its arguments named as the fault catalogue names them.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/report/flight_log.h"

namespace hitl::report {

/// A time or duration beyond this (or not a number: "nan", "inf") is no fault change.
inline constexpr double kMaxFaultTime_s = 1e9;

/// One STATUSTEXT of a fault starting or ending, parsed; nullopt when `text` is not one.
struct FaultChangeText {
  double t_s = 0;                     ///< the simulator's time in the text
  std::string label;                  ///< "imu-vibration:8,90"
  bool started = false;
  std::optional<double> duration_s;   ///< "(5 s)" after a start
};
std::optional<FaultChangeText> parse_fault_change(std::string_view text);

/// The windows of the faults the simulator (`simulator_source`, as FlightLog's events name it) said
/// started and ended, in start order; an end matches the earliest open window of the same label;
/// a window still open when the log ends has no end_s. On the simulator's clock the text's time is
/// used, else the event's.
std::vector<FaultWindow> fault_windows(const std::vector<LogEvent>& events, bool simulated_time,
                                       const std::string& simulator_source = "simulator");

/// "amp_m_s2 8, freq_hz 90" for the label's arguments, named by the fault catalogue ("8, 90" for a
/// fault it does not know; "" with none).
std::string named_fault_args(const std::string& label);

}  // namespace hitl::report
