#include "engine/hil/session.h"

#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/common/clock.h"
#include "engine/hil/client_services.h"
#include "engine/hil/pacer.h"
#include "engine/hil/pause_clock.h"
#include "engine/hil/recording.h"
#include "engine/hil/sensor_messages.h"
#include "engine/hil/snapshot_builder.h"
#include "engine/hil/stack_link.h"
#include "engine/hil/step_check.h"
#include "engine/hil/traffic.h"
#include "engine/mavlink/enums.h"
#include "engine/mavlink/wire_units.h"
#include "engine/model/multicopter.h"
#include "engine/model/touchdown_monitor.h"
#include "engine/sensors/sensor_suite.h"
#include "engine/telemetry/health.h"
#include "engine/vehicle/trajectory_pilot.h"

namespace hitl::hil {

struct Session::Impl {
  SessionConfig config;
  mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  std::unique_ptr<model::Multicopter> model;
  std::optional<sensors::SensorSuite> sensors;
  model::TouchdownMonitor touchdowns;
  Traffic traffic;
  Recording recording;
  PauseClock clock;
  std::unique_ptr<StackLink> stack;         ///< the board or PX4 SITL, lockstep
  std::unique_ptr<ClientServices> services;  ///< client port, status, truth, VIO
  std::optional<Pacer> pacer;
  std::optional<DataPaths> paths;
  std::optional<vehicle::TrajectoryPilot> pilot;
  mavlink::FrameEncoder pilot_encoder{mavlink::kGcsSystemId, mavlink::kCompIdMissionPlanner};  ///< a GCS's identity
  Eigen::Vector3d pilot_origin_ENU_m = Eigen::Vector3d::Zero();

  // Operator controls (the dashboard): requests from other threads, taken at the next step.
  std::atomic<bool> pause_wanted{false};
  std::atomic<bool> reset_wanted{false};
  bool resumed = false;       ///< the first step after a pause: no answer is owed for it
  double time_offset_s = 0;   ///< simulated time before the last reset: the wire's clock never goes back
  uint64_t resets = 0;

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
  Status step(EventSink& events) {
    const double now_s = monotonic_s();
    drain(now_s);
    services->send_status(now_s, start_wall_s, status(now_s));
    services->serve(events);
    say_record_failure(events);
    if (take_controls(events)) return Ok{};  // paused: the model holds, nothing is sent
    // Lockstep waits for the answer to the last HIL_SENSOR; a step shorter than the IMU period sends none every step.
    if (!std::exchange(resumed, false) && std::exchange(sensor_sent, false))
      stack->lockstep_wait(events, [&] { drain(monotonic_s()); });
    model->set_motor_commands(stack->actuators().commands(clock.unpaused_s(monotonic_s())));
    if (auto st = model->step(); !st) return st;
    const auto& state = model->state();
    touchdowns.observe(state);
    const auto frame = sensors->sample_due(state);
    say_imu_saturated(events);
    const double sent_s = monotonic_s();
    const uint64_t t_us = mavlink::wire::s_to_us(sim_time_s());
    send_messages(frame, t_us, sent_s, events);
    stack->flush();
    stack->actuators().take_new();  // answers counted from here on belong to these sensors
    if (services->send_vio_if_due(frame.truth, t_us, sim_time_s())) paths->on_odometry(sent_s);
    services->send_truth_if_due(frame.truth, t_us, sim_time_s());
    say_send_errors(events);
    stack->check_answered(events);
    return Ok{};
  }

  void drain(double now_s) {
    stack->drain(now_s, [&](const mavlink::Frame& f, double t_s) {
      paths->on_stack_frame(f, t_s);
      if (pilot) pilot->on_board_frame(f);
      services->route_from_stack(f, t_s);
    });
    services->drain(now_s);
  }

  /// HIL_SENSOR and HIL_GPS for what was sampled, the pilot's sticks (-t), HEARTBEAT once a second.
  void send_messages(const sensors::SensorFrame& frame, uint64_t t_us, double sent_s, EventSink& events) {
    if (frame.imu || frame.mag || frame.baro) {
      stack->send(make_hil_sensor(frame, t_us));
      sensor_sent = true;
      if (stack->lockstep() && frame.imu) stack->actuators().expect_answer_to(t_us);
      paths->on_hil_sensor(frame.imu.has_value(), frame.mag.has_value(), frame.baro.has_value(), sent_s);
      stack->on_hil_sensor_sent(monotonic_s());
    }
    if (frame.gps) {
      stack->send(make_hil_gps(*frame.gps, t_us));
      paths->on_hil_gps(sent_s);
    }
    if (pilot) fly_pilot(model->state(), events);
    if (sim_time_s() + 1e-9 >= next_heartbeat_s) {
      next_heartbeat_s += 1.0;
      mavlink::msg::Heartbeat hb;
      hb.type = static_cast<uint8_t>(mavlink::MavType::Generic);
      hb.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Invalid);
      hb.system_status = static_cast<uint8_t>(mavlink::MavState::Active);
      hb.mavlink_version = mavlink::kMavlinkVersion;
      stack->send(hb);
    }
  }

  /// -t: the trajectory pilot flies on ground truth, as the spec's trajectory_rc plugin does.
  void fly_pilot(const model::VehicleState& state, EventSink& events) {
    vehicle::PilotPose pose;
    const Eigen::Vector3d p = state.p_ENU_m - pilot_origin_ENU_m;
    pose.p_ENU_m = {p.x(), p.y(), p.z()};
    pose.v_ENU_m_s = {state.v_ENU_m_s.x(), state.v_ENU_m_s.y(), state.v_ENU_m_s.z()};
    const Eigen::Matrix3d R = state.q_FLU_to_ENU.toRotationMatrix();
    pose.yaw_ENU_rad = std::atan2(R(1, 0), R(0, 0));
    auto out = pilot->step(time_offset_s + state.time_s, pose);
    pilot->observe_truth(time_offset_s + state.time_s, pose);  // the session's pilot flies on truth itself
    mavlink::FrameBuffer buf;
    for (const auto& c : out.commands) stack->forward({buf.data(), pilot_encoder.encode(c, buf)});
    if (out.rc) stack->forward({buf.data(), pilot_encoder.encode(*out.rc, buf)});
    if (out.event) events.on_event({pilot->state() == vehicle::PilotState::Failed ? Severity::Error : Severity::Info, *out.event});
  }

  /// Takes the operator's pause and reset requests; true while paused (the step does nothing).
  bool take_controls(EventSink& events) {
    if (const bool want = pause_wanted.load(); want != clock.paused()) {
      char text[96];
      if (want) {
        clock.pause(monotonic_s());
        std::snprintf(text, sizeof text, "paused at %.1f s: the model holds, no sensor data is sent", sim_time_s());
      } else {
        clock.resume(monotonic_s());
        resumed = true;
        std::snprintf(text, sizeof text, "resumed at %.1f s", sim_time_s());
      }
      events.on_event({Severity::Info, text});
    }
    if (reset_wanted.exchange(false)) {
      time_offset_s += model->state().time_s;  // the wire's clock carries on
      model->reset();
      sensors->reset();
      touchdowns.on_reset();
      ++resets;
      char text[96];
      std::snprintf(text, sizeof text, "reset to home at rest, motors stopped (time carries on at %.1f s)", sim_time_s());
      events.on_event({Severity::Info, text});
    }
    return clock.paused();
  }

  // --- what is said once -----------------------------------------------------------------------
  void say_record_failure(EventSink& events) {
    if (auto text = recording.take_failure(); !text.empty()) events.on_event({Severity::Error, text});
  }

  /// Each destination's first refused send, said at once (later ones are counted: send_errors).
  void say_send_errors(EventSink& events) {
    for (const auto& text : stack->take_send_errors()) events.on_event({Severity::Error, text});
    for (const auto& text : services->take_send_errors()) events.on_event({Severity::Error, text});
  }

  void say_imu_saturated(EventSink& events) {
    const auto& saturation = sensors->imu().saturation();
    if (warned_imu_saturated || (saturation.accel == 0 && saturation.gyro == 0)) return;
    warned_imu_saturated = true;
    const auto& imu = config.vehicle.sensors.imu;
    char text[256];
    std::snprintf(text, sizeof text,
                  "IMU at full scale (accel +-%.1f g, gyro +-%.0f deg/s, sensors.imu.*_range): a sample was clipped at "
                  "t = %.2f s, as the real sensor would; counted (imu_saturated)",
                  imu.accel_range_m_s2 / 9.80665, imu.gyro_range_rad_s * 180.0 / M_PI, sim_time_s());
    events.on_event({Severity::Warning, text});
  }

  // --- status and snapshot -----------------------------------------------------------------------
  SessionStatus status(double now_s) const {
    SessionStatus s;
    s.paused = clock.paused();
    s.recent_real_time_factor = recent_rtf;
    s.late_ticks = pacer->stats().late;
    for (const auto& p : paths->stats(now_s))
      if (!p.outgoing && p.stats.since_last_s >= 0 && p.stats.since_last_s < telemetry::kStaleAfter_s)
        s.actuator_rate_hz = p.stats.rate_hz;
    return s;
  }

  void publish() {
    const double now_s = monotonic_s();
    auto s = make_snapshot({config, messages, model->state(), rest_altitude_m, sim_time_s(), now_s - start_wall_s,
                            recent_rtf, traffic, *stack, *services, pacer->stats(), *sensors, touchdowns,
                            pilot ? &*pilot : nullptr, paths->stats(now_s), clock.paused(), resets, recording.error()});
    std::lock_guard<std::mutex> lock(snapshot_mutex);
    published = std::move(s);
  }

  void roll_window() {
    const double now = monotonic_s();
    const double dt = now - window_start_wall_s;
    if (dt <= 0) return;
    traffic.roll(dt);
    recent_rtf = (sim_time_s() - window_start_sim_s) / dt;
    paths->roll(now, config.speed > 0 ? config.speed : recent_rtf);
    window_start_wall_s = now;
    window_start_sim_s = sim_time_s();
  }
};

Expected<std::unique_ptr<Session>> Session::create(const SessionConfig& config) {
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  s.config = config;
  model::VehicleConfig vehicle = config.noise ? config.vehicle : model::with_noise_disabled(config.vehicle);
  auto mc = model::Multicopter::create(vehicle, config.world, config.seed);
  if (!mc) return mc.error();
  s.model = std::move(mc.value());
  s.sensors.emplace(vehicle, config.world, config.seed);
  s.rest_altitude_m = s.model->state().p_ENU_m.z();
  if (!(config.vio_rate_hz > 0)) return Error{"--vio-rate must be > 0"};
  if (!(config.truth_rate_hz >= 0)) return Error{"--truth-rate must be >= 0 (0: no truth to clients)"};
  if (!(config.speed >= 0)) return Error{"--speed must be >= 0 (0: as fast as possible)"};
  if (!std::isfinite(config.actuator_timeout_s) || !(config.actuator_timeout_s > 0))
    return Error{"--actuator-timeout must be a finite number > 0"};
  if (!std::isfinite(config.lockstep_timeout_s) || !(config.lockstep_timeout_s > 0))
    return Error{"--lockstep-timeout must be a finite number > 0"};
  if (auto st = check_step_divides_sensor_periods(config.world.physics.step_s, vehicle); !st) return st.error();

  // s.config, not config: the parts keep a reference to it.
  auto stack = StackLink::open(s.config, s.messages, s.traffic, s.recording, s.clock);
  if (!stack) return stack.error();
  s.stack = std::move(stack.value());
  auto services = ClientServices::open(s.config, s.messages, *s.stack, s.traffic, s.recording);
  if (!services) return services.error();
  s.services = std::move(services.value());
  if (config.trajectory) {
    if (config.link == FlightStackLink::SitlTcp)
      return Error{"-t: PX4 SITL takes only HIL messages on its simulator link; fly the trajectory with "
                   "`hitl fly trajectory` against its GCS port instead"};
    vehicle::PilotConfig pc;
    pc.home_alt_msl_m = config.world.home.alt_m;
    pc.mode = config.trajectory_mode;
    s.pilot.emplace(*config.trajectory, pc);
    s.pilot_origin_ENU_m = s.model->state().p_ENU_m;
  }
  if (!config.record_path.empty()) {
    auto w = mavlink::TlogWriter::open(config.record_path);
    if (!w) return w.error();
    s.recording = Recording(std::move(w.value()));
  }
  s.pacer.emplace(config.world.physics.step_s, config.speed);  // one step of simulated time per tick
  s.paths.emplace(config);
  return std::unique_ptr<Session>(new Session(std::move(impl)));
}

Session::Session(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

std::string Session::describe() const {
  const auto& c = impl_->config;
  char speed[64];
  std::snprintf(speed, sizeof speed, c.speed > 0 ? ", speed %gx" : ", as fast as possible", c.speed);
  return impl_->stack->describe() + impl_->services->describe() + speed;
}

namespace {

void ask_for_realtime(EventSink& events) {
  sched_param sp{};
  sp.sched_priority = 50;
  const bool fifo = sched_setscheduler(0, SCHED_FIFO, &sp) == 0;
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  events.on_event({fifo && locked ? Severity::Info : Severity::Warning,
                   std::string("--realtime: SCHED_FIFO ") + (fifo ? "granted" : "not permitted") + ", mlockall " +
                       (locked ? "granted" : "not permitted") +
                       (fifo && locked ? "" : " (run as root or grant CAP_SYS_NICE and CAP_IPC_LOCK)")});
}

}  // namespace

Expected<Session::EndReason> Session::run(const std::atomic<bool>& stop, Observer& observer) {
  Impl& s = *impl_;
  if (!s.config.noise)
    observer.on_event({Severity::Warning,
                       "--no-noise: PX4 marks a sensor stale after ~100 identical values, so a flight stack on the "
                       "other end will refuse to arm; use it for tests only"});
  if (s.config.realtime) ask_for_realtime(observer);
  if (s.config.link == FlightStackLink::SitlTcp && !s.stack->wait_for_sitl(stop, observer)) return EndReason::Stopped;
  // The default 50 us timer slack would show up as jitter in every HIL_SENSOR interval.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  s.start_wall_s = monotonic_s();
  s.window_start_wall_s = s.start_wall_s;
  s.pacer->start();
  double next_status_s = s.start_wall_s + 1.0;
  double next_publish_s = s.start_wall_s;
  EndReason reason = EndReason::Stopped;
  for (;;) {
    if (stop.load()) break;
    if (s.config.duration_s > 0 && s.sim_time_s() + 1e-9 >= s.config.duration_s) {
      reason = EndReason::Duration;
      break;
    }
    if (auto st = s.step(observer); !st) {
      s.publish();
      return Error{st.error().message};
    }
    if (s.pilot && s.pilot->finished()) {
      reason = s.pilot->state() == vehicle::PilotState::Done ? EndReason::TrajectoryDone : EndReason::TrajectoryFailed;
      break;
    }
    s.stack->check_clock_ahead(observer);
    if (s.stack->lockstep_dead(observer)) {
      reason = EndReason::FlightStackGone;
      break;
    }
    if (s.stack->gone()) {
      observer.on_event({Severity::Error, "PX4 SITL disconnected; PX4 never reconnects to a simulator, so this session "
                                          "ends (restart PX4 and hitl sim together)"});
      reason = EndReason::FlightStackGone;
      break;
    }
    const double now = monotonic_s();
    if (now >= next_publish_s) {  // the snapshot, ten times a second
      next_publish_s = now + 0.1;
      s.publish();
    }
    if (now >= next_status_s) {
      next_status_s += 1.0;
      s.roll_window();
      s.publish();
      observer.on_status(snapshot());
    }
    s.pacer->wait_next(&stop);
  }
  s.recording.flush();
  s.say_record_failure(observer);
  s.roll_window();
  s.publish();
  return reason;
}

void Session::set_paused(bool paused) { impl_->pause_wanted.store(paused); }

void Session::request_reset() { impl_->reset_wanted.store(true); }

SessionSnapshot Session::snapshot() const {
  std::lock_guard<std::mutex> lock(impl_->snapshot_mutex);
  return impl_->published;
}

}  // namespace hitl::hil
