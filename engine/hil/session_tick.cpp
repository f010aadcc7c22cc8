// The session's tick (docs/architecture.md "The session"): one step of simulated time, in the
// design's order. Runs on the one thread that owns time.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "base/common/clock.h"
#include "engine/hil/sensor_messages.h"
#include "engine/hil/session_impl.h"
#include "engine/frames/frames.h"
#include "engine/hil/snapshot_builder.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/wire_units.h"
#include "engine/telemetry/health.h"
#include "engine/telemetry/px4_mode.h"
#include "base/mavlink/messages.h"

namespace hitl::hil {

namespace {

/// MAV_LANDED_STATE in the emulated board's words (its snapshot's landed_state), so a campaign's
/// criterion on the landed state reads the same against either flight stack.
std::string landed_state_word(uint8_t landed_state) {
  switch (static_cast<mavlink::MavLandedState>(landed_state)) {
    case mavlink::MavLandedState::OnGround: return "on_ground";
    case mavlink::MavLandedState::InAir: return "in_air";
    case mavlink::MavLandedState::Takeoff: return "takeoff";
    case mavlink::MavLandedState::Landing: return "landing";
    case mavlink::MavLandedState::Undefined: return "undefined";
  }
  return "state " + std::to_string(landed_state);
}

}  // namespace

Status Session::Impl::step(EventSink& events) {
  // Drain: the flight stack's link and the client port.
  const double now_s = monotonic_s();
  drain(now_s);
  say_record_failure(events);
  if (take_controls(events)) {  // paused: the model holds, nothing is sent to the flight stack
    serve_clients(now_s, events);
    return Ok{};
  }
  // Lockstep wait for the answer to the last HIL_SENSOR (a step shorter than the IMU period sends
  // none every step, and none is owed right after a pause).
  if (!std::exchange(resumed, false) && std::exchange(sensor_sent, false))
    stack->lockstep_wait(events, [&] { drain(monotonic_s()); });
  // Actuator commands, physics step.
  // (actuators-stale: the model holds the last commands it had, whatever the board sends)
  if (!fault_schedule.active().actuators_stale) model->set_motor_commands(stack->actuators().commands(clock.unpaused_s(monotonic_s())));
  if (auto st = model->step(); !st) return st;
  const auto& state = model->state();
  touchdowns.observe(state);
  apply_faults(events);
  // Sensors due at this time, with the active sensor faults.
  auto frame = sensors->sample_due(state, fault_schedule.active().units);
  sensor_faults->apply(fault_schedule.active(), sim_time_s(), frame, state.rotor_speed_rad_s);
  sensors->deliver(frame, state.time_s);  // --board-timing: as late as the board's path reads them
  say_imu_saturated(events);
  // Messages, flushed as one datagram to the flight stack; then VIO and truth.
  const double sent_s = monotonic_s();
  const uint64_t t_us = mavlink::wire::s_to_us(sim_time_s());
  send_messages(frame, t_us, sent_s, events);
  stack->flush();
  stack->actuators().take_new();  // answers counted from here on belong to these sensors
  if (services->send_vio_if_due(frame.truth, t_us, sim_time_s(), fault_schedule.active())) paths->on_odometry(sent_s);
  services->send_truth_if_due(frame.truth, t_us, sim_time_s());
  // What clients are owed, after the flight stack's datagram: the status burst and the client
  // queue never delay a HIL_SENSOR.
  serve_clients(now_s, events);
  say_send_errors(events);
  stack->check_answered(events);
  return Ok{};  // the run loop publishes the snapshot
}

void Session::Impl::serve_clients(double now_s, EventSink& events) {
  if (services->status_due(now_s, sim_time_s()))  // once a second (of wall time; the loop latency's also of simulated time)
    services->send_status(now_s, sim_time_s(), start_wall_s, status(now_s));
  services->serve(events);
}

void Session::Impl::apply_faults(EventSink& events) {
  std::vector<FaultRequest> requests;
  {
    std::lock_guard<std::mutex> lock(fault_requests_mutex);
    requests.swap(fault_requests);
  }
  std::vector<faults::FaultChange> cleared;
  for (auto& r : requests) {
    if (r.start && r.start->kind == faults::FaultKind::SensorUnit) {  // started by hand on a unit that is off: said, not started
      if (const auto off = sensors::unit_off_for_fault(config.sensor_units, r.start->unit_fault); !off.empty()) {
        const SessionEvent e{Severity::Warning, "fault " + r.start->name() + " not started: " + off, std::nullopt};
        services->announce(e.severity, e.text);
        events.on_event(e);
        continue;
      }
    }
    if (r.start) fault_schedule.start_now(std::move(*r.start));
    else for (auto& c : fault_schedule.clear(r.clear_name, sim_time_s())) cleared.push_back(std::move(c));
  }
  if (fault_schedule.empty()) return;
  const faults::VehicleObservation seen{model->state().p_ENU_m.z() - rest_altitude_m, stack->actuators().armed(), board_mode};
  auto changes = fault_schedule.update(sim_time_s(), seen);
  changes.insert(changes.begin(), cleared.begin(), cleared.end());
  for (auto& change : changes) {
    SessionEvent e{change.refused ? Severity::Warning : Severity::Info, change.text(), std::nullopt};
    services->announce(e.severity, e.text);
    e.fault = std::move(change);
    events.on_event(e);
  }
  const auto& active = fault_schedule.active();
  for (std::size_t i = 0; i < active.motor_effectiveness.size(); ++i) model->set_motor_effectiveness(i, active.motor_effectiveness[i]);
  stack->set_link_faults(active.hil_link, sim_time_s());
  services->set_vio_link_faults(active.vio_link, sim_time_s());
  sensors->imu().set_noise_scale(active.imu_noise_scale);
  sensors->gps().set_noise_scale(active.gps_noise_scale);
  model->set_wind_event(frames::ned_to_enu(active.wind_NED_m_s), active.turbulence_sigma_m_s, active.turbulence_tau_s);
  model->set_external_force_ENU_N({0.0, 0.0, -active.payload_kg * config.world.gravity_m_s2});  // payload: its weight
}

void Session::Impl::wait_next_tick(const std::atomic<bool>& stop) {
  // Held datagrams due before the next tick are sent on time, between ticks.
  for (;;) {
    const auto hil_s = stack->next_delayed_s(), vio_s = services->next_vio_delayed_s();
    if (!hil_s && !vio_s) break;
    const double due_s = std::min(hil_s.value_or(vio_s.value_or(0)), vio_s.value_or(hil_s.value_or(0)));
    if (stop.load() || due_s >= pacer->next_due_s()) break;
    sleep_until_monotonic_s(due_s);
    stack->release_delayed(monotonic_s());
    services->release_vio_delayed(monotonic_s());
  }
  pacer->wait_next(&stop);
}

void Session::Impl::drain(double now_s) {
  stack->drain(now_s, [&](const mavlink::Frame& f, double t_s) {
    paths->on_stack_frame(f, t_s);
    if (f.is<mavlink::msg::HilActuatorControls>()) loop_latency->on_actuator(f.as<mavlink::msg::HilActuatorControls>().time_usec, t_s);
    if (f.is<mavlink::msg::Heartbeat>()) {  // the board's mode, for the scenario's conditions
      const auto hb = f.as<mavlink::msg::Heartbeat>();
      if (hb.autopilot != static_cast<uint8_t>(mavlink::MavAutopilot::Invalid)) {
        board_mode = telemetry::px4_mode_name(hb.base_mode, hb.custom_mode);
        stack_state.heard = true;
        stack_state.armed = (hb.base_mode & mavlink::mode_flag::kSafetyArmed) != 0;
        stack_state.mode = board_mode;
      }
    }
    if (f.is<mavlink::msg::ExtendedSysState>()) stack_state.landed_state = landed_state_word(f.as<mavlink::msg::ExtendedSysState>().landed_state);
    if (pilot) pilot->on_board_frame(f);
    services->route_from_stack(f, t_s);
  });
  services->drain(now_s);
}

void Session::Impl::send_messages(const sensors::SensorFrame& frame, uint64_t t_us, double sent_s, EventSink& events) {
  if (frame.imu || frame.mag || frame.baro) {
    stack->send(make_hil_sensor(frame, t_us));
    sensor_sent = true;
    if (stack->lockstep() && frame.imu) stack->actuators().expect_answer_to(t_us);
    if (frame.imu) loop_latency->on_hil_sensor_sent(t_us, sent_s);
    paths->on_hil_sensor(frame.imu.has_value(), frame.mag.has_value(), frame.baro.has_value(), sent_s);
    stack->on_hil_sensor_sent(monotonic_s());
  }
  if (frame.gps) {
    stack->send(make_hil_gps(*frame.gps, t_us));
    paths->on_hil_gps(sent_s);
  }
  // The sensor units' messages (DISTANCE_SENSOR, ...), each as its unit encodes it.
  sensors->units().send(frame.units, t_us, [&](const auto& message) { stack->send(message); });
  if (pilot) fly_pilot(model->state(), events);
  if (sim_time_s() + 1e-9 >= next_heartbeat_s) {
    next_heartbeat_s += 1.0;
    stack->send(mavlink::simulator_heartbeat());
  }
}

void Session::Impl::fly_pilot(const model::VehicleState& state, EventSink& events) {
  // -t: the trajectory flight flies on ground truth, as the spec's trajectory_rc plugin does, and is
  // scored on it.
  const vehicle::PilotPose truth{{state.p_ENU_m.x(), state.p_ENU_m.y(), state.p_ENU_m.z()},
                                 {state.v_ENU_m_s.x(), state.v_ENU_m_s.y(), state.v_ENU_m_s.z()},
                                 frames::yaw_ENU_rad(state.q_FLU_to_ENU)};
  auto out = pilot->step(time_offset_s + state.time_s, truth, truth);
  if (pilot_record && out.reference)
    pilot_record->setpoint(static_cast<uint32_t>(mavlink::wire::s_to_us(sim_time_s()) / 1000), *out.reference, out.tracking_error_m);
  if (pilot_record && out.event)
    pilot_record->note(pilot->state() == vehicle::PilotState::Failed ? Severity::Error : Severity::Info, *out.event);
  mavlink::FrameBuffer buf;
  for (const auto& c : out.commands) stack->forward({buf.data(), pilot_encoder.encode(c, buf)});
  if (out.rc) stack->forward({buf.data(), pilot_encoder.encode(*out.rc, buf)});
  if (out.manual) stack->forward({buf.data(), pilot_encoder.encode(*out.manual, buf)});
  if (out.event) events.on_event({pilot->state() == vehicle::PilotState::Failed ? Severity::Error : Severity::Info, *out.event});
}

bool Session::Impl::take_controls(EventSink& events) {
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

void Session::Impl::say_record_failure(EventSink& events) {
  if (auto text = recording.take_failure(); !text.empty()) events.on_event({Severity::Error, text});
}

void Session::Impl::say_send_errors(EventSink& events) {
  for (const auto& text : stack->take_send_errors()) events.on_event({Severity::Error, text});
  for (const auto& text : services->take_send_errors()) events.on_event({Severity::Error, text});
}

void Session::Impl::say_imu_saturated(EventSink& events) {
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

SessionStatus Session::Impl::status(double now_s) const {
  SessionStatus s;
  s.paused = clock.paused();
  s.recent_real_time_factor = recent_rtf;
  s.late_ticks = pacer->stats().late;
  if (const auto latency = loop_latency->summary().latency; latency.count > 0) {
    s.loop_latency_p50_us = latency.p50_us;
    s.loop_latency_p99_us = latency.p99_us;
    s.loop_latency_max_us = latency.max_us;
  }
  for (const auto& p : paths->stats(now_s))
    if (!p.outgoing && p.stats.since_last_s >= 0 && p.stats.since_last_s < telemetry::kStaleAfter_s)
      s.actuator_rate_hz = p.stats.rate_hz;
  if (px4) s.px4_instance = stack->connected() ? px4->instance().index : -1;
  return s;
}

void Session::Impl::publish() {
  const double now_s = monotonic_s();
  auto s = make_snapshot({config, messages, model->state(), rest_altitude_m, sim_time_s(), now_s - start_wall_s,
                          recent_rtf, traffic, *stack, *services, pacer->stats(), *sensors, touchdowns,
                          pilot ? &*pilot : nullptr, paths->stats(now_s), clock.paused(), resets, recording.error()});
  s.active_faults = fault_schedule.active_texts();
  s.pending_faults = fault_schedule.pending_texts();
  s.faults = fault_schedule.records();
  s.loop_latency = loop_latency->summary();
  s.hil_link_faults = stack->link_faults().counts();
  s.vio_link_faults = services->vio_link_faults().counts();
  s.stack_state = stack_state;
  if (px4) s.px4 = {px4->instance().index, px4->build().version, px4->build().build_dir, px4->work_dir(), px4->console_path()};
  std::lock_guard<std::mutex> lock(snapshot_mutex);
  published = std::move(s);
}

void Session::Impl::roll_window() {
  const double now = monotonic_s();
  const double dt = now - window_start_wall_s;
  if (dt <= 0) return;
  traffic.roll(dt);
  recent_rtf = (sim_time_s() - window_start_sim_s) / dt;
  paths->roll(now, config.speed > 0 ? config.speed : recent_rtf);
  window_start_wall_s = now;
  window_start_sim_s = sim_time_s();
}

}  // namespace hitl::hil
