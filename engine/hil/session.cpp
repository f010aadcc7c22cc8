#include "engine/hil/session.h"

#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <cmath>
#include <cstdio>

#include "base/common/clock.h"
#include "engine/hil/session_impl.h"
#include "engine/hil/step_check.h"
#include "engine/telemetry/imu_noise_statement.h"

namespace hitl::hil {

Expected<std::unique_ptr<Session>> Session::create(const SessionConfig& config) {
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  s.config = config;
  model::VehicleConfig vehicle = config.noise ? config.vehicle : model::with_noise_disabled(config.vehicle);
  auto mc = model::Multicopter::create(vehicle, config.world, config.seed);
  if (!mc) return mc.error();
  s.model = std::move(mc.value());
  s.sensors.emplace(vehicle, config.world, config.seed,
                    config.noise ? config.sensor_units : sensors::without_noise(config.sensor_units));
  if (config.board_timing != "none") {
    const auto timing = sensors::data_path_timing_model(config.board_timing);
    if (!timing) return Error::usage("--board-timing: unknown model '" + config.board_timing + "' (" + sensors::board_timing_model_list() + ")");
    s.sensors->set_data_path_timing(*timing, config.seed);
  }
  for (const auto& f : config.faults) {  // a sensor unit's fault acts on its unit: refused while it is off
    if (f.kind != faults::FaultKind::SensorUnit) continue;
    if (const auto off = sensors::unit_off_for_fault(config.sensor_units, f.unit_fault); !off.empty())
      return Error::usage("fault " + f.name() + ": " + off);
  }
  s.rest_altitude_m = s.model->state().p_ENU_m.z();
  if (!(config.vio_rate_hz > 0)) return Error::input("the VIO rate (vio_rate_hz) must be > 0");
  if (!(config.truth_rate_hz >= 0)) return Error::input("the truth rate (truth_rate_hz) must be >= 0 (0: no truth to clients)");
  if (!(config.speed >= 0)) return Error::input("the speed (real-time factor) must be >= 0 (0: as fast as possible)");
  if (!std::isfinite(config.actuator_timeout_s) || !(config.actuator_timeout_s > 0))
    return Error::input("the actuator timeout (actuator_timeout_s) must be a finite number > 0");
  if (!std::isfinite(config.lockstep_timeout_s) || !(config.lockstep_timeout_s > 0))
    return Error::input("the lockstep timeout (lockstep_timeout_s) must be a finite number > 0");
  if (auto st = check_step_divides_sensor_periods(config.world.physics.step_s, vehicle); !st) return st.error();

  // s.config, not config: the parts keep a reference to it.
  if (s.config.px4) {  // --px4: the stack link of the first free PX4 instance; PX4 starts in run()
    auto open_stack = [&s](const px4::Px4Instance& instance) -> Expected<std::unique_ptr<StackLink>> {
      auto peer = StackPeer::decide(s.config, instance);
      if (!peer) return peer.error();
      return StackLink::open(s.config, std::move(peer.value()), s.messages, s.traffic, s.recording, s.clock);
    };
    auto launch = Px4Launch::claim(s.config, open_stack, s.stack);
    if (!launch) return launch.error();
    s.px4 = std::move(launch.value());
  } else {
    auto peer = StackPeer::decide(s.config);
    if (!peer) return peer.error();
    auto stack = StackLink::open(s.config, std::move(peer.value()), s.messages, s.traffic, s.recording, s.clock);
    if (!stack) return stack.error();
    s.stack = std::move(stack.value());
  }
  auto services = ClientServices::open(s.config, s.messages, *s.stack, s.traffic, s.recording);
  if (!services) return services.error();
  s.services = std::move(services.value());
  if (config.trajectory) {
    if (!s.stack->peer().carries_client_traffic())
      return Error::usage(std::string("a trajectory cannot be flown over ") + s.stack->peer().name() +
                          "'s TCP simulator link, which takes only HIL messages; fly it with `hitl fly trajectory` "
                          "against PX4's GCS port instead");
    vehicle::PilotConfig pc;
    pc.home_alt_msl_m = config.world.home.alt_m;
    pc.mode = config.trajectory_mode;
    if (s.px4) pc.target_system = s.px4->instance().sysid();  // PX4 instance N is system N+1
    s.pilot.emplace(*config.trajectory, pc);
  }
  if (!config.record_path.empty()) {
    auto w = mavlink::TlogWriter::open(config.record_path);
    if (!w) return w.error();
    s.recording = Recording(std::move(w.value()));
  }
  if (s.recording.active() && s.pilot) {
    Recording* recording = &s.recording;
    s.pilot_record.emplace([recording](std::span<const uint8_t> frame) { recording->record(frame); }, config.sysid, config.protocol);
  }
  if (!std::isfinite(config.spin_us) || config.spin_us < 0 || config.spin_us > Pacer::kMaxSpin_s * 1e6)
    return Error::input("the spin (spin_us) must be 0 to " + std::to_string(static_cast<int>(Pacer::kMaxSpin_s * 1e6)) + " us");
  // One step of simulated time per tick.
  s.pacer.emplace(config.world.physics.step_s, config.speed, config.spin_us * 1e-6);
  s.paths.emplace(config, s.stack->lockstep());
  s.loop_latency.emplace(s.stack->lockstep());
  s.fault_schedule = faults::FaultSchedule(config.faults);
  s.sensor_faults.emplace(config.world.atmosphere);
  return std::unique_ptr<Session>(new Session(std::move(impl)));
}

Session::Session(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

std::string Session::describe() const {
  const auto& c = impl_->config;
  char speed[64];
  std::snprintf(speed, sizeof speed, c.speed > 0 ? ", speed %gx" : ", as fast as possible", c.speed);
  return impl_->stack->describe() + (impl_->px4 ? impl_->px4->describe() : "") + impl_->services->describe() + speed;
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

/// PX4's console warnings and errors ("PX4: WARN  [failsafe] Failsafe activated", px4_launch.h) go
/// to the observer and also where the session's own notes go: the clients and the recording, as the
/// simulator's STATUSTEXT on the simulator's clock, so that a report or a campaign's expectation
/// sees what PX4 said only on its console.
class Px4ConsoleNotes : public EventSink {
 public:
  Px4ConsoleNotes(EventSink& next, ClientServices& services) : next_(next), services_(services) {}
  void on_event(const SessionEvent& e) override {
    next_.on_event(e);
    if (e.text.rfind("PX4: ", 0) == 0) services_.announce(e.severity, e.text);
  }

 private:
  EventSink& next_;
  ClientServices& services_;
};

}  // namespace

Expected<Session::EndReason> Session::run(const std::atomic<bool>& stop, Observer& observer) {
  Impl& s = *impl_;
  if (s.px4) {
    if (auto started = s.px4->start(observer); !started) return started.error();
  }
  auto end = s.run_steps(stop, observer);
  if (s.px4) {
    if (auto said = s.px4->check(observer, s.stack->connected()); said && end) end = *said;  // PX4 ended it as it ended
    s.px4->stop(s.stack->actuators().ever_received(), observer);
  }
  return end;
}

Expected<Session::EndReason> Session::Impl::run_steps(const std::atomic<bool>& stop, Session::Observer& observer) {
  Impl& s = *this;
  if (!s.config.noise)
    observer.on_event({Severity::Warning,
                       "--no-noise: PX4 marks a sensor stale after ~100 identical values, so a flight stack on the "
                       "other end will refuse to arm; use it for tests only"});
  if (s.config.realtime) ask_for_realtime(observer);
  if (!s.stack->peer().reports_mode()) {  // a mode condition could never hold: said before it silently never fires
    for (const auto& f : s.config.faults) {
      const bool on_mode = (f.start_when && f.start_when->mode) || (f.end_when && f.end_when->mode);
      if (on_mode)
        observer.on_event({Severity::Warning, "fault " + (f.id.empty() ? f.name() : f.id) + ": its 'mode' condition can never hold: " +
                                                  s.stack->peer().name() + "'s simulator link does not carry PX4's mode "
                                                  "(PX4 started by hitl sim --px4 does)"});
    }
  }
  if (auto connected = s.stack->wait_until_connected(stop, observer, [&s, &observer]() -> std::optional<Error> {
        return s.px4 ? s.px4->check(observer, s.stack->connected()) : std::nullopt;
      });
      !connected || !*connected) {  // PX4 gave up, or stopped while waiting: the summary still says what was pending
    s.start_wall_s = monotonic_s();
    s.publish();
    if (!connected) return connected.error();
    return EndReason::Stopped;
  }
  // The default 50 us timer slack would show up as jitter in every HIL_SENSOR interval.
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  s.start_wall_s = monotonic_s();
  s.window_start_wall_s = s.start_wall_s;
  s.pacer->start();
  // What the IMU is set to, into the recording and to the clients (hitl report marks it on its Allan plot).
  const model::ImuConfig imu = s.config.noise ? s.config.vehicle.sensors.imu : model::with_noise_disabled(s.config.vehicle).sensors.imu;
  s.services->announce(Severity::Info, telemetry::imu_noise_statement({s.config.imu_profile, imu.gyro.noise_density, imu.gyro.bias_instability,
                                                                      imu.accel.noise_density, imu.accel.bias_instability}));
  double next_status_s = s.start_wall_s + 1.0;
  double next_publish_s = s.start_wall_s;
  double next_px4_check_s = s.start_wall_s;
  EndReason reason = EndReason::Stopped;
  for (;;) {
    if (stop.load()) break;
    if (s.config.duration_s > 0 && s.sim_time_s() + 1e-9 >= s.config.duration_s) {
      reason = EndReason::Duration;
      break;
    }
    if (auto st = s.step(observer); !st) {
      s.publish();
      return st.error();
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
    if (s.px4 && (s.stack->gone() || monotonic_s() >= next_px4_check_s)) {  // PX4's console, and whether it still runs
      next_px4_check_s = monotonic_s() + 0.1;
      Px4ConsoleNotes notes(observer, *s.services);
      if (auto ended = s.px4->check(notes, s.stack->connected(), s.stack->gone())) {
        s.publish();
        return *ended;
      }
    }
    if (s.stack->gone()) {
      observer.on_event({Severity::Error, s.stack->peer().lost_text()});
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
      observer.on_status(s.published_copy());
    }
    s.wait_next_tick(stop);
  }
  s.recording.flush();
  s.say_record_failure(observer);
  s.roll_window();
  s.publish();
  return reason;
}

void Session::set_paused(bool paused) { impl_->pause_wanted.store(paused); }

void Session::request_reset() { impl_->reset_wanted.store(true); }

void Session::start_fault(faults::FaultSpec spec) {
  std::lock_guard<std::mutex> lock(impl_->fault_requests_mutex);
  if (impl_->fault_requests.size() < Impl::kMaxFaultRequests) impl_->fault_requests.push_back({std::move(spec), {}});
}

void Session::clear_faults(std::string name) {
  std::lock_guard<std::mutex> lock(impl_->fault_requests_mutex);
  if (impl_->fault_requests.size() < Impl::kMaxFaultRequests) impl_->fault_requests.push_back({std::nullopt, std::move(name)});
}

SessionSnapshot Session::snapshot() const { return impl_->published_copy(); }

SessionSnapshot Session::Impl::published_copy() const {
  std::lock_guard<std::mutex> lock(snapshot_mutex);
  return published;
}

}  // namespace hitl::hil
