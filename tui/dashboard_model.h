// Everything one frame of the dashboard shows, as plain values (btop's cpu_info): sources fill it
// from their snapshots (sim_dashboard.h, inspect_dashboard.h), the panels draw it (panels.h).
// A panel a source cannot fill is absent (nullopt) or carries the reason it is "n/a".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/common/severity.h"
#include "engine/telemetry/estimator_flags.h"
#include "engine/telemetry/health.h"

namespace hitl::tui {

using telemetry::Health;

/// One data path of the spec's "Data Flow Rates" table, or one message on an inspected link.
struct PathRow {
  std::string name;                ///< "IMU", "GPS", ... or the message name
  std::string message;             ///< the MAVLink message carrying it
  bool outgoing = true;            ///< host -> board
  double expected_hz = 0;          ///< 0: nothing to hold it to
  double rate_hz = 0;
  double jitter_ms = 0;            ///< standard deviation of the intervals
  double max_gap_ms = 0;
  std::optional<double> loss_pct;  ///< when the host can see it
  uint64_t count = 0;
  Health health = Health::Good;
  std::string note;                ///< replaces the health word: "paused", "stale", ...
};

struct PathsPanel {
  std::vector<PathRow> rows;
  std::string caption;             ///< under the rows when there is room: how to read the rates
};

struct CounterRow {
  std::string name;                ///< the status text's label
  std::string short_name;          ///< for narrow panels
  uint64_t count = 0;
  std::optional<double> rate_hz;   ///< none before two polls
  double expected_hz = 0;
  bool stalled = false;            ///< stopped incrementing: a red mark
  Health health = Health::Good;
};

struct DspHitlPanel {
  std::optional<std::string> unavailable;  ///< "n/a: <reason>"
  bool running = false;
  std::vector<CounterRow> counters;
  double age_s = -1;               ///< since the last good poll
};

struct TestRatio {
  std::string name;                ///< "vel", "pos h", "pos v", "mag"
  double value = 0;                ///< innovation test ratio; < 1 passes
};

struct EkfPanel {
  std::optional<std::string> unavailable;
  std::vector<telemetry::EstimatorFlag> flags;
  std::vector<TestRatio> ratios;
  std::optional<double> horizontal_error_m;  ///< estimate against the simulator's truth
  std::optional<double> vertical_error_m;
  std::optional<double> attitude_error_deg;
  std::optional<double> horizontal_rms_m;
  std::optional<double> attitude_rms_deg;
  std::optional<double> horizontal_accuracy_m;  ///< the estimator's own 1-sigma
  std::optional<double> vertical_accuracy_m;
  std::string error_note;          ///< why there is no error figure ("no ground truth: not a simulation")
};

struct VehiclePanel {
  std::optional<std::string> unavailable;
  bool armed = false;
  std::string mode;
  std::string landed;              ///< "on ground", "in air", ...; empty when not heard
  bool in_air = false;             ///< disarming now needs a confirmation
  std::optional<bool> ready_to_arm;
  std::optional<double> battery_V;
  std::optional<double> battery_A;
  std::optional<double> battery_pct;
  std::optional<double> altitude_m;        ///< the autopilot's estimate above its origin
  std::optional<double> truth_altitude_m;  ///< the simulator's, above the rest pose
  std::optional<std::array<double, 4>> motors;             ///< commands 0..1
  std::optional<std::array<double, 4>> rotor_speed_rad_s;  ///< from the simulator
  double rotor_max_rad_s = 0;      ///< full scale of the rotor bars
};

using Severity = ::hitl::Severity;  // base/common/severity.h

struct LogLine {
  double t_s = 0;                  ///< on the dashboard's clock (simulated seconds for sim and demo; else since it started)
  Severity severity = Severity::Info;
  std::string text;
  int repeats = 1;                 ///< a STATUSTEXT said this many times within a short window: "(xN)"
};

/// Loop latency at the board (engine/hil/loop_latency.h): the sim dashboard's, on tall terminals.
struct LatencyPanel {
  std::string matched;  ///< "by echo" (lockstep) or "next message"
  uint64_t count = 0;
  double p50_us = 0, p95_us = 0, p99_us = 0, max_us = 0;
  double limit_us = 0;  ///< above this the figure is yellow (lockstep: one step); 0: none
  struct Bin {
    std::string label;  ///< "<250 us", "1-2 ms", ">=256 ms"
    uint64_t count = 0;
  };
  std::vector<Bin> bins;  ///< the histogram's fixed bins
};

struct LinkField {
  std::string label;
  std::string value;
  Health health = Health::Good;
};

/// One data path's rate over the graphs' window, against its expected rate.
struct RateGraph {
  std::string name;
  double expected_hz = 0;          ///< 0: nothing to hold it to (drawn against its own peak)
  std::vector<double> rate_hz;     ///< oldest first, NaN where the path was absent
};

/// The rolling graphs (graph_history.h): samples oldest first, one per sample period, NaN where
/// there was no value; at most `capacity` each.
struct GraphsPanel {
  double window_s = 60;
  std::size_t capacity = 600;
  std::vector<double> truth_altitude_m;
  std::vector<double> estimate_altitude_m;
  std::vector<double> tracking_error_m;  ///< all NaN (or empty) when no trajectory flew in the window
  std::vector<RateGraph> rates;
};

/// A fault active now (the sim dashboard; docs/faults.md): the fault menu lists them to clear.
struct ActiveFault {
  std::string name;              ///< "motor": what `clear NAME` ends
  std::string text;              ///< "motor:2,0.6", as the status lines name it
  double started_s = 0;          ///< simulated time
  std::optional<double> left_s;  ///< of its duration; none: until cleared (or its scenario's end_when)
};

struct DashboardModel {
  std::string title;               ///< "hitl sim", "hitl inspect"
  std::string state;               ///< "running", "PAUSED", ...
  Health state_health = Health::Good;
  std::string clock;               ///< "sim 123.4 s"
  PathsPanel paths;
  std::optional<DspHitlPanel> dsp_hitl;
  std::optional<EkfPanel> ekf;
  std::optional<VehiclePanel> vehicle;
  std::optional<LatencyPanel> latency;
  std::vector<LogLine> messages;   ///< oldest first
  std::string link_partner;        ///< the Link panel's title: who is on the other end
  Health link_health = Health::Good;
  std::vector<LinkField> link;
  std::string keys;                ///< the action keys that work here ("adtlprfs"; the footer and help list them); empty: it only shows
  bool trajectory_running = false; ///< f then asks whether to stop it
  std::string busy;                ///< an action in flight, for the footer ("arming ...")
  std::optional<LogLine> outcome;  ///< the last key's outcome, pinned in the header
  std::optional<GraphsPanel> graphs;  ///< the sim's rolling graphs, drawn when the terminal has room
  std::vector<ActiveFault> active_faults;  ///< oldest first (the sim dashboard's; named on the state line too)
};

}  // namespace hitl::tui
