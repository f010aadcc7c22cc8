// From engine snapshots to the dashboard's plain values (btop's collect()): one function per
// panel, shared by every source that has that snapshot (sim; bridge for the vehicle panels).
#pragma once

#include <string>
#include <vector>

#include "engine/faults/fault_schedule.h"
#include "engine/hil/data_paths.h"
#include "engine/telemetry/dsp_hitl_meter.h"
#include "engine/vehicle/telemetry_feed.h"
#include "tui/dashboard_model.h"

namespace hitl::tui {

/// The session's data paths; expected rates are already at the session's pace. `paused`: rates
/// are not judged (the note says so).
PathsPanel paths_from(const std::vector<hil::DataPathStats>& paths, bool paused, std::string caption);

/// The dsp_hitl counters; expected rates (real time) scaled by `pace` (the real-time factor).
DspHitlPanel dsp_hitl_from(const telemetry::DspHitlView& view, double pace);

/// ESTIMATOR_STATUS and the estimate against the truth, from the telemetry feed.
EkfPanel ekf_from(const vehicle::TelemetryFeedSnapshot& feed);

/// What the autopilot says (armed, mode, landed, battery, altitude); the caller adds the
/// simulator's motors and rotors when it has them.
VehiclePanel vehicle_from(const vehicle::TelemetryFeedSnapshot& feed);

/// The faults active at `sim_time_s` from the session's records (those not ended), oldest first,
/// with what is left of each one's duration.
std::vector<ActiveFault> active_faults_from(const std::vector<faults::FaultRecord>& records, double sim_time_s);
/// For the state line: "faults: gps-loss (27 s left) motor:2,0.6", the first few named and the
/// rest counted ("+5 more (x lists them)"); "" with none.
std::string active_faults_text(const std::vector<ActiveFault>& active);

}  // namespace hitl::tui
