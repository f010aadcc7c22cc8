// A copy of the session's state, handed over whole (the dashboard, status lines, the summary),
// and the builder that reads it off the session's parts once a publish is due. Positions and
// attitude are converted to the wire's NED/FRD by engine/frames, as everywhere else.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/faults/fault_schedule.h"
#include "engine/hil/link_faults.h"
#include "engine/hil/data_paths.h"
#include "engine/hil/loop_latency.h"
#include "engine/sensors/data_path_timing.h"

namespace hitl::hil {

struct StreamCount {
  uint64_t count = 0;
  double rate_hz = 0;  ///< over the last status window (about a second of wall time)
};

/// A copy of the session's state, handed over whole (UI, status lines, summaries).
struct SessionSnapshot {
  double sim_time_s = 0;
  double wall_time_s = 0;
  double real_time_factor = 0;         ///< sim / wall since the start
  double recent_real_time_factor = 0;  ///< over the last window
  std::map<std::string, StreamCount> sent;      ///< by message name
  std::map<std::string, StreamCount> received;  ///< from the flight stack, by message name
  uint64_t send_errors = 0;             ///< messages the kernel refused to send (never counted in `sent`)
  std::string last_send_error;          ///< the latest refusal in words (errno, likely fix); empty when none
  bool connected = false;               ///< SITL: PX4 connected; board: actuators arriving
  std::string partner;                  ///< the flight stack's address
  /// --px4: the PX4 this session started (instance -1 without one).
  struct Px4Started {
    int instance = -1;
    std::string version;   ///< "v1.16.0"; empty when the build does not say
    std::string build_dir;
    std::string work_dir;  ///< its parameters and ULogs (log/)
    std::string console;   ///< its console file
  } px4;
  bool armed = false;                   ///< the last actuator message's armed flag
  /// What the flight stack says of itself: its HEARTBEAT (armed, mode) and EXTENDED_SYS_STATE (landed
  /// state); a board's on its HIL link, PX4's that --px4 started from its GCS instance. Empty (and
  /// heard false) until the stack sent them.
  struct StackState {
    bool heard = false;        ///< a HEARTBEAT from the stack's autopilot
    bool armed = false;        ///< its MAV_MODE_FLAG_SAFETY_ARMED
    std::string mode;          ///< "Position", "Land" (telemetry/px4_mode.h)
    std::string landed_state;  ///< "on_ground", "in_air", "takeoff", "landing", "undefined"; empty: never sent
  } stack_state;
  std::array<double, 4> motor_commands{};
  std::array<double, 4> rotor_speed_rad_s{};
  double altitude_m = 0;                ///< above home at rest: 0 on the ground, as PX4's local position (truth)
  std::array<double, 3> p_NED_m{};      ///< from home at rest (the same origin as altitude_m)
  std::array<double, 4> q_FRD_to_NED{1, 0, 0, 0};
  bool on_ground = true;
  uint64_t steps = 0;
  uint64_t late_ticks = 0;
  uint64_t resyncs = 0;
  double max_lateness_ms = 0;
  uint64_t actuator_clamped = 0;
  uint64_t ignored_other_address = 0;
  uint64_t ignored_other_sysid = 0;
  uint64_t actuator_timeouts = 0;
  uint64_t lockstep_waits = 0;
  uint64_t lockstep_fallbacks = 0;
  uint64_t lockstep_late_answers = 0;   ///< answers to an earlier HIL_SENSOR (time_usec), ignored
  uint64_t lockstep_foreign_clock = 0;  ///< answers whose time_usec echoes no HIL_SENSOR (counted as answers)
  // the IMU's full scale (sensors.imu.*_range): samples clipped
  uint64_t imu_accel_saturated = 0;
  uint64_t imu_gyro_saturated = 0;
  /// --board-timing: the model's name ("" when none) and the delays it applied (sensors/data_path_timing.h).
  std::string board_timing;
  sensors::DataPathTimingFigures board_timing_figures;
  // touchdowns (model::TouchdownMonitor)
  uint64_t touchdowns = 0;
  double max_rebound_m = 0;
  double max_touchdown_speed_m_s = 0;
  double peak_touchdown_accel_m_s2 = 0;
  uint64_t crc_errors = 0;
  uint64_t parse_errors = 0;
  uint64_t clients = 0;
  uint64_t clients_refused = 0;         ///< datagrams from senders beyond the client limit, dropped
  uint64_t client_frames_dropped = 0;   ///< frames to clients dropped: more than the per-step send bound
  uint64_t routed_to_board = 0;
  uint64_t routed_to_clients = 0;
  uint64_t actuator_flags = 0;
  uint64_t actuator_mode = 0;
  // -t: the trajectory pilot
  std::string trajectory_state;  ///< empty without -t; INIT ... DONE / FAILED
  std::string trajectory_failure;
  uint64_t trajectory_samples = 0;
  double trajectory_rms_m = 0;   ///< tracking error against ground truth
  double trajectory_max_m = 0;
  // the data paths, live (the dashboard), and the operator's controls
  std::vector<DataPathStats> paths;
  bool paused = false;
  uint64_t resets = 0;           ///< times the vehicle was put back home
  double speed = 1.0;            ///< --speed (0: as fast as possible)
  bool lockstep = false;
  std::string record_error;      ///< --record failed: the file and why (empty: fine, or not recording)
  // faults (docs/faults.md)
  std::vector<std::string> active_faults;  ///< "gps-loss", "motor:2,0.6"
  std::vector<std::string> pending_faults;  ///< events not started (yet): at the end, never started
  std::vector<faults::FaultRecord> faults; ///< every fault that started, with its start and end
  LinkFaultCounts hil_link_faults;         ///< what the hil-* faults did to datagrams to the flight stack
  LinkFaultCounts vio_link_faults;         ///< what the vio-* link faults did to ODOMETRY
  LoopLatencySummary loop_latency;         ///< HIL_SENSOR -> its HIL_ACTUATOR_CONTROLS, wall time (loop_latency.h)
};

}  // namespace hitl::hil
