#include "engine/hil/stack_link.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "base/common/clock.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/messages.h"
#include "engine/net/open_link.h"

#include <poll.h>

namespace hitl::hil {

bool is_hil_message(uint32_t msgid) {
  return msgid == mavlink::msg::HilSensor::kId || msgid == mavlink::msg::HilGps::kId ||
         msgid == mavlink::msg::HilActuatorControls::kId || msgid == mavlink::msg::HilStateQuaternion::kId;
}

Expected<std::unique_ptr<StackLink>> StackLink::open(const SessionConfig& config, StackPeer peer, const mavlink::MessageSet& messages,
                                                     Traffic& traffic, Recording& recording, const PauseClock& clock) {
  auto link = net::open_link(peer.link(), peer.link_settings());
  if (!link) return link.error();
  std::unique_ptr<net::Link> telemetry;
  if (const auto spec = peer.telemetry_link()) {
    auto opened = net::open_link(*spec, peer.telemetry_link_settings());
    if (!opened) return opened.error();
    telemetry = std::move(opened.value());
  }
  return std::unique_ptr<StackLink>(new StackLink(config, std::move(peer), std::move(link.value()), std::move(telemetry),
                                                  messages, traffic, recording, clock));
}

StackLink::StackLink(const SessionConfig& config, StackPeer peer, std::unique_ptr<net::Link> link,
                     std::unique_ptr<net::Link> telemetry, const mavlink::MessageSet& messages, Traffic& traffic,
                     Recording& recording, const PauseClock& clock)
    : config_(config),
      peer_(std::move(peer)),
      link_(std::move(link)),
      encoder_(config.sysid, config.compid, config.protocol),
      parser_(messages),
      telemetry_(std::move(telemetry)),
      telemetry_parser_(messages),
      traffic_(traffic),
      recording_(recording),
      clock_(clock),
      actuators_(config.actuator_timeout_s),
      link_faults_(config.seed, "hil-drop") {}

Expected<bool> StackLink::wait_until_connected(const std::atomic<bool>& stop, EventSink& events,
                                               const std::function<std::optional<Error>()>& give_up) {
  if (!peer_.connects_in()) return true;
  const std::string local = link_->local_address() ? link_->local_address()->to_string() : "?";
  events.on_event({Severity::Info, std::string("waiting for ") + peer_.name() + " to connect to TCP " + local + "; " + peer_.start_hint()});
  const double wait_start_s = monotonic_s();
  double next_note_s = wait_start_s + 10.0;
  while (!link_->wait_connected(200)) {
    if (stop.load()) return false;
    if (give_up) {
      if (auto e = give_up()) return *e;
    }
    if (monotonic_s() >= next_note_s) {
      next_note_s += 10.0;
      events.on_event({Severity::Info, std::string("still waiting for ") + peer_.name() + " on TCP " + std::to_string(link_->local_address()->port()) +
                                           " (" + std::to_string(static_cast<int>(monotonic_s() - wait_start_s)) + " s)"});
    }
  }
  events.on_event({Severity::Info, std::string(peer_.name()) + " connected from " + link_->peer()->to_string()});
  return true;
}

void StackLink::queue(std::span<const uint8_t> bytes, std::optional<uint32_t> counted_id) {
  if (link_faults_.holding()) {  // hil-drop / hil-delay: the step's frames go out (or not) as one datagram later,
    link_faults_.hold(bytes, counted_id);  // and are recorded then: a recording holds what the board was sent
    return;
  }
  recording_.record(bytes);
  if (!link_->has_room_for(bytes.size())) flush();  // a full datagram is sent first (and its messages counted)
  link_->queue(bytes);
  if (counted_id) ++batch_[*counted_id];  // counted as sent when its datagram is
}

void StackLink::forward(std::span<const uint8_t> bytes) {
  ++routed_to_board_;
  if (!telemetry_) return queue(bytes, std::nullopt);
  recording_.record(bytes);
  queue_telemetry(bytes);
}

void StackLink::queue_telemetry(std::span<const uint8_t> bytes) {
  if (!telemetry_->has_room_for(bytes.size())) (void)telemetry_->flush();  // a full datagram leaves first
  telemetry_->queue(bytes);
}

void StackLink::flush_telemetry() {
  const double now_s = monotonic_s();
  if (now_s >= next_telemetry_heartbeat_s_) {
    next_telemetry_heartbeat_s_ = now_s + 1.0;
    mavlink::FrameBuffer buf;
    // The HIL link's encoder: one sequence for the session's identity, so that a recording of both
    // links shows no false loss (PX4 numbers its two MAVLink instances apart; that one stays).
    if (const std::size_t n = encoder_.encode(mavlink::simulator_heartbeat(), buf)) queue_telemetry({buf.data(), n});
  }
  if (telemetry_->queued_bytes() == 0) return;
  if (const auto st = telemetry_->flush(); !st) traffic_.count_failed(1, st.error().message);
}

void StackLink::flush() {
  if (telemetry_) flush_telemetry();
  if (link_faults_.holding()) {
    link_faults_.close_datagram(monotonic_s());
    release_delayed(monotonic_s());
    return;
  }
  send_batch();
}

void StackLink::release_delayed(double now_s) {
  link_faults_.release_due(now_s, [&](LinkFaults::Datagram& d) {
    auto held = std::exchange(batch_, std::move(d.counts));  // frames queued since (a client's) wait for their own flush
    for (const auto& f : d.frames) {
      recording_.record(f);
      if (!link_->has_room_for(f.size())) send_batch();
      link_->queue(f);
    }
    send_batch();
    batch_ = std::move(held);
  });
}

void StackLink::send_batch() {
  // The counts are zeroed, not erased: the few ids a step sends keep their entries, so a step
  // allocates nothing here.
  if (!link_->connected()) {  // PX4 SITL not (or no longer) connected: nothing leaves, nothing is counted
    (void)link_->flush();
    for (auto& entry : batch_) entry.second = 0;
    return;
  }
  const auto st = link_->flush();
  for (auto& [id, n] : batch_) {
    if (n == 0) continue;
    if (st) traffic_.count_sent(id, n);
    else if (!link_->closed()) traffic_.count_failed(n, st.error().message);  // a lost stream is gone(), not a send error
    n = 0;
  }
}

void StackLink::drain(double now_s, const FrameHandler& on_frame) {
  // One pointer captured: the handler fits std::function's small buffer, no allocation per step.
  struct Context {
    StackLink& self;
    const FrameHandler& on_frame;
    double now_s;
  } c{*this, on_frame, now_s};
  link_->drain(
      parser_,
      [&c](const mavlink::Frame& f) {
        c.self.recording_.record(f.bytes());
        c.self.traffic_.count_received(f.msgid);
        c.on_frame(f, c.now_s);
        if (f.is<mavlink::msg::HilActuatorControls>())
          c.self.actuators_.on_message(f.as<mavlink::msg::HilActuatorControls>(), f.sysid, c.self.clock_.unpaused_s(c.now_s));
      },
      kMaxDatagramsPerDrain);
  if (!telemetry_) return;
  telemetry_->drain(
      telemetry_parser_,
      [&c](const mavlink::Frame& f) {
        if (is_hil_message(f.msgid)) return;  // the HIL messages belong to the simulator link
        c.self.recording_.record(f.bytes());
        c.self.traffic_.count_received(f.msgid);
        c.on_frame(f, c.now_s);
      },
      kMaxDatagramsPerDrain);
}

void StackLink::on_hil_sensor_sent(double wall_s) {
  if (first_sensor_wall_s_ < 0) first_sensor_wall_s_ = wall_s;
}

std::string StackLink::peer_text() const {
  return link_->peer() ? link_->peer()->to_string() : std::string("the flight stack");
}

std::string StackLink::describe() const {
  const std::string local = link_->local_address() ? link_->local_address()->to_string() : "?";
  const char* lockstep = peer_.lockstep() ? " (lockstep)" : "";
  if (peer_.connects_in()) {
    std::string out = std::string("serving ") + peer_.name() + " on TCP " + local + lockstep;
    if (telemetry_ && telemetry_->peer()) out += ", its GCS MAVLink at UDP " + telemetry_->peer()->to_string();
    return out;
  }
  return "HIL_SENSOR/HIL_GPS to " + peer_text() + " from " + local + lockstep;
}

// --- lockstep --------------------------------------------------------------------------------

void StackLink::lockstep_wait(EventSink& events, const std::function<void()>& drain_all) {
  if (!lockstep()) return;
  if (!actuators_.ever_received()) {
    // PX4 SITL sends nothing during its first ~1.1 s: step on until it answers. A board (hitl target
    // --lockstep) answers from the first HIL_SENSOR: wait for that once, so that the steps never run
    // ahead of it and the same input gives the same session (docs/replay.md "Deterministic
    // sessions"); one that does not is not waited for again until heard (not a fallback).
    if (!peer_.answers_first_sensor() || waited_first_) return;
    waited_first_ = true;
    const double deadline = monotonic_s() + config_.lockstep_timeout_s;
    while (!actuators_.ever_received() && !gone()) {
      release_delayed(monotonic_s());  // hil-delay: the HIL_SENSOR awaited may still be held
      double wait_s = deadline - monotonic_s();
      if (const auto due_s = next_delayed_s()) wait_s = std::min(wait_s, std::max(0.0, *due_s - monotonic_s()));
      if (deadline - monotonic_s() <= 0) return;
      if (link_->wait_readable(static_cast<int>(std::ceil(wait_s * 1000)))) drain_all();
    }
    actuators_.take_new();
    return;
  }
  if (stalled_) {
    // After a wait ran out, step on at the pace (bounded wall time) until the board is heard again.
    if (actuators_.take_heard() == 0) return;
    stalled_ = false;
    events.on_event({Severity::Info, "lockstep: the flight stack answers again; waiting for each answer again"});
  }
  ++lockstep_counters_.waits;
  const double deadline = monotonic_s() + config_.lockstep_timeout_s;
  while (actuators_.take_new() == 0 && !gone()) {
    release_delayed(monotonic_s());  // hil-delay: the HIL_SENSOR awaited may still be held
    // A stack on this host answers within microseconds: poll for it a moment before sleeping.
    pollfd fd{link_->fd(), POLLIN, 0};
    if (fd.fd >= 0 && busy_poll_.spin({&fd, 1})) {
      drain_all();
      if (actuators_.take_new() > 0) break;
      continue;
    }
    const double left_s = deadline - monotonic_s();
    double wait_s = left_s;
    if (const auto due_s = next_delayed_s()) wait_s = std::min(wait_s, std::max(0.0, *due_s - monotonic_s()));
    if (left_s <= 0 || !link_->wait_readable(static_cast<int>(std::ceil(wait_s * 1000)))) {
      if (monotonic_s() < deadline) continue;
      ++lockstep_counters_.fallbacks;
      busy_poll_.on_nothing();
      stalled_ = true;
      actuators_.take_heard();
      if (!warned_lockstep_) {
        warned_lockstep_ = true;
        events.on_event({Severity::Warning, "lockstep: no HIL_ACTUATOR_CONTROLS within " +
                                                std::to_string(static_cast<int>(config_.lockstep_timeout_s * 1000)) +
                                                " ms of the last HIL_SENSOR; stepping on without waiting until it "
                                                "answers again (counted)"});
      }
      return;
    }
    drain_all();
  }
}

bool StackLink::lockstep_dead(EventSink& events) {
  if (!lockstep() || peer_.link_tells_loss() || !actuators_.last_heard_s()) return false;
  const double silent_s = clock_.unpaused_s(monotonic_s()) - *actuators_.last_heard_s();
  if (silent_s < kLockstepGiveUp_s) return false;
  char text[512];
  std::snprintf(text, sizeof text,
                "lockstep: no HIL_ACTUATOR_CONTROLS from %s for %.0f s; ending the session. The flight stack "
                "stopped answering: restart it, then hitl sim (hitl target --lockstep: restart it or check it is "
                "still running; a PX4 board: restart PX4 on it, voxl-px4-hitl start)",
                peer_text().c_str(), silent_s);
  events.on_event({Severity::Error, text});
  return true;
}

void StackLink::check_clock_ahead(EventSink& events) {
  if (warned_clock_ahead_ || !lockstep() || !actuators_.ever_received()) return;
  const int64_t offset_us = actuators_.last_echo_offset_us();
  char text[512];
  const bool echoes = peer_.answer_clock() == AnswerClock::SensorTime;
  if (echoes && offset_us >= static_cast<int64_t>(ActuatorInput::kEchoWindow_us)) {
    std::snprintf(text, sizeof text,
                  "lockstep: PX4 SITL's answers are stamped %.1f s ahead of this session's clock: it still runs on "
                  "an earlier session's time and cannot go back, so it will not take these sensors as new. Restart "
                  "PX4 SITL together with hitl sim",
                  static_cast<double>(offset_us) * 1e-6);
    events.on_event({Severity::Warning, text});
  } else if (!echoes && actuators_.counters().foreign_clock >= 10) {
    std::snprintf(text, sizeof text,
                  "lockstep: the board stamps its answers with its own clock, not the HIL_SENSOR's time_usec (a "
                  "PX4 board in HIL mode does; hitl target --lockstep echoes it): each answer counts, late ones "
                  "cannot be told apart");
    events.on_event({Severity::Info, text});
  } else {
    return;
  }
  warned_clock_ahead_ = true;
}

// --- no answer -------------------------------------------------------------------------------

void StackLink::check_answered(EventSink& events) {
  if (warned_no_answer_ || first_sensor_wall_s_ < 0 || actuators_.ever_received() ||
      monotonic_s() - first_sensor_wall_s_ <= config_.no_answer_warning_s)
    return;
  warned_no_answer_ = true;
  events.on_event({Severity::Warning, no_answer_text()});
}

std::string StackLink::no_answer_text() const {
  const uint64_t errors = traffic_.send_errors;
  if (errors > 0 && traffic_.delivered() == 0)
    return "no HIL_ACTUATOR_CONTROLS: nothing reached the flight stack, every send failed (" + std::to_string(errors) +
           " messages; " + traffic_.last_send_error + ")";
  if (errors > 0)
    return peer_.no_answer_cause(peer_text(), config_.no_answer_warning_s) + "; and " + std::to_string(errors) + " messages could not be sent (" +
           traffic_.last_send_error + ")";
  return peer_.no_answer_cause(peer_text(), config_.no_answer_warning_s);
}

}  // namespace hitl::hil
