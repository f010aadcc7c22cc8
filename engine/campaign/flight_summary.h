// A campaign flight's summary: `hitl sim --json`'s final summary (engine/hil/snapshot_json.h) plus
// how the flight ended, the rates per simulated second, the flight stack's own figures and the
// flight's parameters. Criteria name its figures by dotted path (docs/campaigns.md).
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/campaign/flight.h"
#include "engine/hil/session_snapshot.h"
#include "engine/report/flight_log.h"

namespace hitl::campaign {

/// What the flight stack itself said and counted, under "stack": the emulated board's snapshot; for
/// PX4, its state from its GCS instance (the session's stack_state) and the simulator link's counts
/// (TCP: what hitl sent is what PX4 received).
struct StackFigures {
  bool armed = false;
  std::string mode;
  std::string landed_state;
  uint64_t hil_sensor_received = 0;
  uint64_t hil_gps_received = 0;
  uint64_t odometry_received = 0;
  uint64_t actuators_sent = 0;
  uint64_t malformed = 0;
};

/// Events kept in a flight's summary (the recording holds them all).
inline constexpr std::size_t kMaxSummaryEvents = 500;

/// The summary JSON of one flight. `end` is the session's end ("trajectory_done", ...). `log`, the
/// flight's recording read back (engine/report), gives "ekf_test_ratios" (each ratio's largest over
/// the flight, ESTIMATOR_STATUS) and "events" (STATUSTEXT, armed, disarmed, mode changes on the
/// simulator's clock); without it they are null and empty.
nlohmann::json flight_summary_json(const Campaign& campaign, const Flight& flight, const hil::SessionSnapshot& snapshot,
                                   const std::string& end, const StackFigures& stack, const report::FlightLog* log);

/// The value at a dotted path ("trajectory.rms_m"), or nullptr when absent.
const nlohmann::json* figure_at(const nlohmann::json& summary, const std::string& path);

/// "square/none/seed-1: trajectory DONE, tracking RMS 0.21 m max 0.48 m, 2 touchdowns; 41.0 s simulated in 3.2 s"
std::string summary_line(const Flight& flight, const nlohmann::json& summary);

}  // namespace hitl::campaign
