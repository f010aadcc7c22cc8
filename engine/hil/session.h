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
#include "engine/hil/data_paths.h"
#include "engine/hil/session_config.h"
#include "engine/hil/session_events.h"
#include "engine/hil/session_snapshot.h"

namespace hitl::hil {

class Session {
 public:
  class Observer : public EventSink {
   public:
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
  /// Starts a fault now (the dashboard's fault prompt), at the next step; said as any fault is.
  void start_fault(faults::FaultSpec spec);
  /// Ends the active faults named `name` (all of them when empty) at the next step.
  void clear_faults(std::string name);
  /// One line: where the session sends and listens.
  std::string describe() const;

 private:
  struct Impl;
  explicit Session(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hitl::hil
