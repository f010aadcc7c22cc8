// The HITL session: one thread owns time. Every 4 ms step: read what arrived (non-blocking),
// apply the latest actuator commands, step the engine, sample the sensors that are due, send
// (HIL_SENSOR, HIL_GPS, ODOMETRY, HEARTBEAT), and publish a snapshot for the UI. Local clients
// are routed to and from the board. Never prints: events and snapshots go to an observer.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/common/severity.h"
#include "engine/hil/data_paths.h"
#include "engine/hil/session_config.h"

namespace hitl::hil {

using Severity = ::hitl::Severity;  // base/common/severity.h

struct SessionEvent {
  Severity severity = Severity::Info;
  std::string text;
};

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
  bool armed = false;
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
};

class Session {
 public:
  class Observer {
   public:
    virtual ~Observer() = default;
    virtual void on_event(const SessionEvent& /*event*/) {}
    /// About once a second of wall time.
    virtual void on_status(const SessionSnapshot& /*snapshot*/) {}
  };
  enum class EndReason { Duration, Stopped, FlightStackGone, TrajectoryDone, TrajectoryFailed };

  /// Builds the model and sensors and opens every socket: a port in use, a bad address or a bad
  /// config is an Error here, before anything runs.
  static Expected<std::unique_ptr<Session>> create(const SessionConfig& config);
  ~Session();

  /// Runs until --duration of simulated time, `stop`, or (SITL) PX4 disconnecting. An integration
  /// blow-up ends the run with an Error naming the step.
  Expected<EndReason> run(const std::atomic<bool>& stop, Observer& observer);

  /// Thread-safe: the latest snapshot (published about 10 times a second, and at the end).
  SessionSnapshot snapshot() const;

  /// Thread-safe operator controls, taken at the next step. Paused, the model holds and nothing is
  /// sent to the flight stack (lockstep: the board's clock stops with it; wall clock: the board
  /// sees no sensor data, as with a paused Gazebo); clients are still routed. Actuator timeouts
  /// do not count the time spent paused.
  void set_paused(bool paused);
  /// Puts the vehicle back home at rest with the motors stopped (sensor noise restarts from its
  /// seed); simulated time on the wire carries on, so the flight stack sees no clock jump.
  void request_reset();
  /// One line: where the session sends and listens.
  std::string describe() const;

 private:
  struct Impl;
  explicit Session(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hitl::hil
