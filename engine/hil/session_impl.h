// The session's state and its tick, shared by session.cpp (create, run) and session_tick.cpp
// (the step). Internal to engine/hil.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>

#include "engine/hil/client_services.h"
#include "engine/hil/data_paths.h"
#include "engine/hil/loop_latency.h"
#include "engine/hil/pacer.h"
#include "engine/hil/pause_clock.h"
#include "engine/hil/px4_launch.h"
#include "engine/hil/recording.h"
#include "engine/vehicle/pilot_record.h"
#include "engine/hil/session.h"
#include "engine/hil/stack_link.h"
#include "engine/hil/traffic.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/message_set.h"
#include "engine/faults/fault_schedule.h"
#include "engine/faults/sensor_faults.h"
#include "engine/model/multicopter.h"
#include "engine/model/touchdown_monitor.h"
#include "engine/sensors/sensor_suite.h"
#include "engine/vehicle/trajectory_flight.h"

namespace hitl::hil {

struct Session::Impl {
  SessionConfig config;
  mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  std::unique_ptr<model::Multicopter> model;
  std::optional<sensors::SensorSuite> sensors;
  model::TouchdownMonitor touchdowns;
  Traffic traffic;
  Recording recording;
  std::optional<vehicle::PilotRecord> pilot_record;  ///< -t with --record: the pilot's setpoints, errors and states
  PauseClock clock;
  std::unique_ptr<StackLink> stack;         ///< the board or PX4 SITL, lockstep
  std::unique_ptr<Px4Launch> px4;           ///< --px4: the PX4 this session starts and stops (else null)
  std::unique_ptr<ClientServices> services;  ///< client port, status, truth, VIO
  std::optional<Pacer> pacer;
  std::optional<DataPaths> paths;
  std::optional<LoopLatency> loop_latency;  ///< HIL_SENSOR -> its HIL_ACTUATOR_CONTROLS (loop_latency.h)
  std::optional<vehicle::TrajectoryFlight> pilot;
  faults::FaultSchedule fault_schedule;  ///< --fault, --scenario
  std::optional<faults::SensorFaults> sensor_faults;  ///< what the sensor faults hold (stuck readings)
  mavlink::FrameEncoder pilot_encoder{mavlink::kGcsSystemId, mavlink::kCompIdMissionPlanner};  ///< a GCS's identity

  // Operator controls (the dashboard): requests from other threads, taken at the next step.
  std::atomic<bool> pause_wanted{false};
  std::atomic<bool> reset_wanted{false};
  struct FaultRequest {
    std::optional<faults::FaultSpec> start;  ///< none: clear
    std::string clear_name;                  ///< "" with no start: every active fault
  };
  static constexpr std::size_t kMaxFaultRequests = 64;  ///< between two steps; more are ignored
  std::mutex fault_requests_mutex;
  std::vector<FaultRequest> fault_requests;
  bool resumed = false;       ///< the first step after a pause: no answer is owed for it
  double time_offset_s = 0;   ///< simulated time before the last reset: the wire's clock never goes back
  uint64_t resets = 0;

  std::string board_mode;      ///< the board's PX4 mode from its HEARTBEAT (scenario conditions)
  SessionSnapshot::StackState stack_state;  ///< the stack's HEARTBEAT and EXTENDED_SYS_STATE (board_mode among them)
  double rest_altitude_m = 0;  ///< the body origin's height at rest at home: altitude 0, as PX4's local position
  double next_heartbeat_s = 0;
  double start_wall_s = 0;
  bool sensor_sent = false;    ///< the last step sent a HIL_SENSOR (lockstep owes it an answer)
  bool warned_imu_saturated = false;
  double window_start_wall_s = 0;
  double window_start_sim_s = 0;
  double recent_rtf = 0;

  mutable std::mutex snapshot_mutex;
  SessionSnapshot published;

  /// Simulated time since the session started, across resets.
  double sim_time_s() const { return time_offset_s + model->state().time_s; }

  // --- the tick: drain, lockstep wait, actuator commands, physics, sensors, messages, flush ----
  Status step(EventSink& events);
  void drain(double now_s);
  /// The status once it is due, and the client port's queue (routed frames, truth, status).
  void serve_clients(double now_s, EventSink& events);
  /// HIL_SENSOR and HIL_GPS for what was sampled, the pilot's sticks (-t), HEARTBEAT once a second.
  void send_messages(const sensors::SensorFrame& frame, uint64_t t_us, double sent_s, EventSink& events);
  /// Starts and ends the faults due at this step's time (said as events) and sets the model's
  /// motors and the HIL link from what is active; the sensor and VIO faults are read where they act.
  void apply_faults(EventSink& events);
  /// -t: the trajectory pilot flies on ground truth, as the spec's trajectory_rc plugin does.
  void fly_pilot(const model::VehicleState& state, EventSink& events);
  /// Takes the operator's pause and reset requests; true while paused (the step does nothing).
  bool take_controls(EventSink& events);
  // --- what is said once -----------------------------------------------------------------------
  void say_record_failure(EventSink& events);
  /// Each destination's first refused send, said at once (later ones are counted: send_errors).
  void say_send_errors(EventSink& events);
  void say_imu_saturated(EventSink& events);
  // --- status and snapshot -----------------------------------------------------------------------
  SessionStatus status(double now_s) const;
  void publish();
  /// A copy of the last published snapshot (Session::snapshot(), the status the run loop reports).
  SessionSnapshot published_copy() const;
  void roll_window();
  /// The steps from start to end (Session::run around it starts and stops an owned PX4).
  Expected<Session::EndReason> run_steps(const std::atomic<bool>& stop, Session::Observer& observer);
  /// The pacer's wait for the next tick, waking for the HIL link's held datagrams as they fall due.
  void wait_next_tick(const std::atomic<bool>& stop);
};

}  // namespace hitl::hil
