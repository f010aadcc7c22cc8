// A scenario file: faults at simulated times, for `hitl sim --scenario FILE` (docs/faults.md
// "Scenario files"). JSON:
//
//   {"description": "GPS loss in the climb, then a weak motor",      (optional)
//    "events": [{"at_s": 20, "fault": "gps-loss", "duration_s": 10},
//               {"at_s": 15, "fault": "motor", "args": [2, 0.6]},
//               {"at_s": 5,  "fault": "hil-delay", "args": "20", "duration_s": 5}]}
//
// at_s: start, simulated seconds (>= 0); fault: a name from the catalogue (fault_spec.h); args: a
// JSON array of numbers or a string "2,0.6" (optional when the fault takes none); duration_s:
// optional, > 0 (none: until the session ends). Unknown keys are refused, as is a file over
// kMaxScenarioFileBytes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/faults/fault_spec.h"

namespace hitl::faults {

inline constexpr std::size_t kMaxScenarioFileBytes = 1 << 20;  ///< 1 MiB: thousands of events
inline constexpr std::size_t kMaxScenarioEvents = 10000;

/// The events of a scenario's text (`where` names it in errors: "scenario 'x.json'").
Expected<std::vector<FaultSpec>> parse_scenario(const std::string& text, const std::string& where,
                                                const Suggest& suggest = {});
/// Reads (bounded) and parses a scenario file; errors name the file, the event and the problem.
Expected<std::vector<FaultSpec>> load_scenario(const std::string& path, const Suggest& suggest = {});

}  // namespace hitl::faults
