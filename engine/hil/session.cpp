#include "engine/hil/session.h"

#include "engine/common/clock.h"
#include <sched.h>
#include <sys/prctl.h>
#include <sys/mman.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <algorithm>
#include <optional>

#include "engine/frames/frames.h"
#include "engine/hil/actuator_input.h"
#include "engine/hil/data_paths.h"
#include "engine/hil/pacer.h"
#include "engine/hil/sensor_messages.h"
#include "engine/hil/step_check.h"
#include "engine/mavlink/enums.h"
#include "engine/mavlink/frame_encoder.h"
#include "engine/mavlink/frame_parser.h"
#include "engine/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "engine/mavlink/wire_units.h"
#include "engine/model/multicopter.h"
#include "engine/model/touchdown_monitor.h"
#include "engine/net/client_port.h"
#include "engine/router/router.h"
#include "engine/net/tcp_server.h"
#include "engine/net/udp_endpoint.h"
#include "engine/sensors/sensor_suite.h"
#include "engine/telemetry/health.h"
#include "engine/vehicle/trajectory_flight.h"

namespace hitl::hil {
namespace {

/// Messages the session itself exchanges with the flight stack; never routed to or from clients.
bool is_hil_message(uint32_t msgid) {
  return msgid == mavlink::msg::HilSensor::kId || msgid == mavlink::msg::HilGps::kId ||
         msgid == mavlink::msg::HilActuatorControls::kId || msgid == mavlink::msg::HilStateQuaternion::kId;
}

/// Per drain, at most this many datagrams from the flight stack's socket and from the client port:
/// a flood waits in the kernel's buffer (and overflows there) instead of stalling the step.
constexpr std::size_t kMaxStackDatagramsPerDrain = 256;
constexpr std::size_t kMaxClientDatagramsPerDrain = 64;

struct Counter {
  uint64_t count = 0;
  uint64_t window = 0;
  double rate_hz = 0;
};

}  // namespace

struct Session::Impl {
  SessionConfig config;
  mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  std::unique_ptr<model::Multicopter> model;
  std::optional<sensors::SensorSuite> sensors;
  mavlink::FrameEncoder encoder{kSimulatorSystemId, kSimulatorComponentId};      ///< the HIL link's sequence
  mavlink::FrameEncoder vio_encoder{kSimulatorSystemId, kVioComponentId};  ///< the VIO link's own sequence
  mavlink::FrameEncoder truth_encoder{kSimulatorSystemId, kSimulatorComponentId};  ///< truth to clients
  std::optional<mavlink::FrameParser> stack_parser;
  std::optional<mavlink::FrameParser> client_parser;

  std::optional<net::UdpEndpoint> hil_udp;
  std::optional<net::SocketAddress> target;
  std::optional<net::TcpServer> sitl_tcp;
  std::vector<uint8_t> tcp_tx;
  std::optional<net::UdpEndpoint> vio;
  std::optional<net::ClientPort> clients;
  router::Router router;  ///< board <-> clients, the same code path as hitl bridge (no dedup: one path)
  router::LinkId board_link = 0, clients_link = 0;
  std::optional<mavlink::TlogWriter> recorder;
  std::optional<vehicle::TrajectoryFlight> pilot;
  mavlink::FrameEncoder pilot_encoder{mavlink::kGcsSystemId, mavlink::kCompIdMissionPlanner};  ///< a GCS's identity

  ActuatorInput actuators{0.5};
  model::TouchdownMonitor touchdowns;
  bool lockstep_stalled = false;  ///< a wait ran out: step on without waiting until the board is heard again
  bool warned_imu_saturated = false;
  bool warned_clock_ahead = false;
  bool lockstep_gave_up = false;
  std::optional<Pacer> pacer;
  std::optional<DataPaths> paths;

  // Operator controls (the dashboard): requests from other threads, taken at the next step.
  std::atomic<bool> pause_wanted{false};
  std::atomic<bool> reset_wanted{false};
  bool paused = false;
  bool resumed = false;          ///< the first step after a pause: no answer is owed for it
  double pause_start_s = 0;
  double paused_total_s = 0;     ///< wall time spent paused (actuator timeouts do not count it)
  double time_offset_s = 0;      ///< simulated time before the last reset: the wire's clock never goes back
  uint64_t resets = 0;

  double rest_altitude_m = 0;  ///< the body origin's height at rest at home: altitude 0, as PX4's local position
  std::map<uint32_t, Counter> sent;
  std::map<uint32_t, uint64_t> batch;  ///< messages in the HIL datagram being built: sent once it is
  uint64_t send_errors = 0;
  std::string last_send_error;
  std::map<uint32_t, Counter> received;
  uint64_t ignored_other_address = 0;
  uint64_t lockstep_waits = 0;
  uint64_t lockstep_fallbacks = 0;
  uint64_t routed_to_board = 0;
  uint64_t routed_to_clients = 0;
  double next_vio_s = 0;
  uint64_t vio_k = 0;
  double next_truth_s = 0;
  uint64_t truth_k = 0;
  double next_status_wall_s = 0;
  double next_heartbeat_s = 0;
  double start_wall_s = 0;
  double first_sensor_wall_s = -1;
  bool warned_no_answer = false;
  bool warned_lockstep = false;
  bool warned_clients_full = false;
  bool warned_record = false;
  bool sensor_sent = false;      ///< the last step sent a HIL_SENSOR (lockstep owes it an answer)
  bool warned_clients_dropped = false;
  bool stack_gone = false;
  double window_start_wall_s = 0;
  double window_start_sim_s = 0;
  double recent_rtf = 0;

  mutable std::mutex snapshot_mutex;
  SessionSnapshot published;

  bool sitl() const { return config.link == FlightStackLink::SitlTcp || config.link == FlightStackLink::SitlUdp; }
  /// Simulated time since the session started, across resets.
  double sim_time_s() const { return time_offset_s + model->state().time_s; }
  /// The monotonic clock without the time spent paused (what actuator timeouts are measured on).
  double unpaused_s(double wall_s) const { return wall_s - paused_total_s - (paused ? wall_s - pause_start_s : 0.0); }
  bool lockstep() const { return config.lockstep || sitl(); }

  const char* name_of(uint32_t id) const {
    const auto* d = messages.find(id);
    return d ? d->name.c_str() : "?";
  }

  // --- sending -------------------------------------------------------------------------------
  void record(std::span<const uint8_t> bytes) {
    if (recorder && recorder->ok()) recorder->write(static_cast<uint64_t>(unix_time_ns() / 1000), bytes);
  }

  /// --record failing (a full disk) is said at once, naming the file and the error; the session
  /// runs on (the board needs its sensors) and ends with an error (SessionSnapshot::record_error).
  void watch_recorder(Observer& observer) {
    if (!recorder || recorder->ok() || warned_record) return;
    warned_record = true;
    observer.on_event({Severity::Error, "--record: " + recorder->error() + "; recording stopped, the session runs on"});
  }

  template <class M>
  void send_to_stack(const M& message) {
    mavlink::FrameBuffer buf;
    const std::size_t n = encoder.encode(message, buf);
    if (n == 0) return;
    const std::span<const uint8_t> bytes(buf.data(), n);
    record(bytes);
    if (sitl_tcp) {
      tcp_tx.insert(tcp_tx.end(), bytes.begin(), bytes.end());
      count_sent(M::kId, 1);
    } else {
      queue_to_stack(bytes);
      ++batch[M::kId];  // counted as sent when its datagram is
    }
  }

  void count_sent(uint32_t id, uint64_t n) {
    auto& c = sent[id];
    c.count += n;
    c.window += n;
  }

  void count_failed(uint64_t n, const std::string& why) {
    send_errors += n;
    last_send_error = why;
  }

  /// Into the HIL datagram being built; a full one is sent first (and its messages counted).
  void queue_to_stack(std::span<const uint8_t> bytes) {
    if (hil_udp->queued_bytes() > 0 && hil_udp->queued_bytes() + bytes.size() > net::UdpEndpoint::kMaxDatagram)
      flush_to_stack();
    (void)hil_udp->queue(bytes);  // never sends: the batch has room
  }

  template <class M>
  void send_to_vio(const M& message) {
    mavlink::FrameBuffer buf;
    const std::size_t n = vio_encoder.encode(message, buf);
    if (n == 0) return;
    record({buf.data(), n});
    if (auto st = vio->send({buf.data(), n}); st) count_sent(M::kId, 1);
    else count_failed(1, st.error().message);
  }

  void flush_to_stack() {
    if (sitl_tcp) {
      if (!tcp_tx.empty() && sitl_tcp->connected() && !sitl_tcp->send(tcp_tx)) stack_gone = true;
      tcp_tx.clear();
    } else {
      const auto st = hil_udp->flush();
      for (const auto& [id, n] : batch) {
        if (st) count_sent(id, n);
        else count_failed(n, st.error().message);
      }
      batch.clear();
    }
  }

  /// Each destination's first failed send, said at once (later ones are counted: send_errors).
  void report_send_errors(Observer& observer) {
    for (auto* ep : {hil_udp ? &*hil_udp : nullptr, vio ? &*vio : nullptr})
      if (ep != nullptr)
        for (const auto& text : ep->take_send_errors()) observer.on_event({Severity::Error, text});
  }

  void forward_to_stack(std::span<const uint8_t> bytes) {
    if (sitl_tcp) tcp_tx.insert(tcp_tx.end(), bytes.begin(), bytes.end());
    else queue_to_stack(bytes);
    record(bytes);
    ++routed_to_board;
  }

  // --- receiving -----------------------------------------------------------------------------
  void on_stack_frame(const mavlink::Frame& f, double now_s) {
    record(f.bytes());
    auto& c = received[f.msgid];
    ++c.count;
    ++c.window;
    paths->on_stack_frame(f, now_s);
    if (pilot) pilot->on_board_frame(f);
    if (f.is<mavlink::msg::HilActuatorControls>()) {
      actuators.on_message(f.as<mavlink::msg::HilActuatorControls>(), f.sysid, unpaused_s(now_s));
    } else if (!is_hil_message(f.msgid) && clients) {
      router.route(f, board_link, now_s);
    }
  }

  void drain(double now_s) {
    if (sitl_tcp) {
      while (sitl_tcp->connected()) {
        auto bytes = sitl_tcp->receive();
        if (!bytes) {
          stack_gone = true;
          break;
        }
        if (bytes->empty()) break;
        stack_parser->feed(*bytes, [&](const mavlink::Frame& f) { on_stack_frame(f, now_s); });
      }
    } else {
      for (std::size_t read = 0; read < kMaxStackDatagramsPerDrain; ++read) {
        auto d = hil_udp->receive();
        if (!d) break;
        if (target && d->from != *target) {  // PX4 answers from its own port; anything else is not our board
          ++ignored_other_address;
          continue;
        }
        stack_parser->parse_datagram(d->bytes, [&](const mavlink::Frame& f) { on_stack_frame(f, now_s); });
      }
    }
    if (clients) {
      clients->receive_some(kMaxClientDatagramsPerDrain, [&](const net::Datagram& d) {
        client_parser->parse_datagram(d.bytes, [&](const mavlink::Frame& f) {
          if (is_hil_message(f.msgid)) return;
          router.route(f, clients_link, now_s, d.from);  // to the board, and to the other clients
        });
      });
    }
  }

  /// Sends what the step queued for clients (bounded per step: net::ClientPortLimits) and says
  /// once when a bound was hit.
  void serve_clients(Observer& observer) {
    if (!clients) return;
    clients->pump();
    const auto& st = clients->stats();
    if (st.refused_datagrams > 0 && !warned_clients_full) {
      warned_clients_full = true;
      observer.on_event({Severity::Warning, "client port: " + std::to_string(clients->limits().max_clients) +
                                                " clients already; datagrams from further senders are dropped (counted: "
                                                "clients_refused) until one goes silent for " +
                                                std::to_string(net::ClientPort::kClientTimeout.count()) + " s"});
    }
    if (st.dropped_frames > 0 && !warned_clients_dropped) {
      warned_clients_dropped = true;
      observer.on_event({Severity::Warning, "client port: more to send than " +
                                                std::to_string(clients->limits().max_datagrams_out) +
                                                " datagrams per step; frames to clients dropped (counted: "
                                                "client_frames_dropped)"});
    }
  }

  bool wait_stack_readable(int timeout_ms) {
    if (sitl_tcp) return sitl_tcp->wait_readable(timeout_ms);
    return hil_udp->wait_readable(timeout_ms);
  }

  // --- the step ------------------------------------------------------------------------------
  void lockstep_wait(Observer& observer) {
    if (!lockstep() || !actuators.ever_received()) return;  // PX4 sends nothing during its first ~1.1 s
    if (lockstep_stalled) {
      // After a wait ran out, step on at the pace (bounded wall time) until the board is heard again.
      if (actuators.take_heard() == 0) return;
      lockstep_stalled = false;
      observer.on_event({Severity::Info, "lockstep: the flight stack answers again; waiting for each answer again"});
    }
    ++lockstep_waits;
    const double deadline = monotonic_s() + config.lockstep_timeout_s;
    while (actuators.take_new() == 0 && !stack_gone) {
      const double left_s = deadline - monotonic_s();
      if (left_s <= 0 || !wait_stack_readable(static_cast<int>(std::ceil(left_s * 1000)))) {
        if (monotonic_s() < deadline) continue;
        ++lockstep_fallbacks;
        lockstep_stalled = true;
        actuators.take_heard();
        if (!warned_lockstep) {
          warned_lockstep = true;
          observer.on_event({Severity::Warning, "lockstep: no HIL_ACTUATOR_CONTROLS within " +
                                                    std::to_string(static_cast<int>(config.lockstep_timeout_s * 1000)) +
                                                    " ms of the last HIL_SENSOR; stepping on without waiting until it "
                                                    "answers again (counted)"});
        }
        return;
      }
      drain(monotonic_s());
    }
  }

  /// Lockstep against a flight stack that stopped answering: after kLockstepGiveUp_s of silence the
  /// session ends (exit 1) saying what to restart, rather than running on without it.
  bool lockstep_dead(Observer& observer) {
    if (!lockstep() || sitl_tcp || !actuators.last_heard_s()) return false;
    const double silent_s = unpaused_s(monotonic_s()) - *actuators.last_heard_s();
    if (silent_s < kLockstepGiveUp_s) return false;
    lockstep_gave_up = true;
    char text[512];
    std::snprintf(text, sizeof text,
                  "lockstep: no HIL_ACTUATOR_CONTROLS from %s for %.0f s; ending the session. The flight stack "
                  "stopped answering: restart it, then hitl sim (hitl target --lockstep: restart it or check it is "
                  "still running; a PX4 board: restart PX4 on it, voxl-px4-hitl start)",
                  target ? target->to_string().c_str() : "the flight stack", silent_s);
    observer.on_event({Severity::Error, text});
    return true;
  }

  /// Lockstep against a flight stack whose answers are not echoes of this session's HIL_SENSORs,
  /// said once. PX4 SITL stamped more than 1 s ahead still runs on an earlier session's clock and
  /// cannot go back in time: restart it. A board on its own clock (PX4 in HIL mode stamps on
  /// arrival) is fine: every answer counts, only late ones cannot be told apart.
  void check_clock_ahead(Observer& observer) {
    if (warned_clock_ahead || !lockstep() || !actuators.ever_received()) return;
    const int64_t offset_us = actuators.last_echo_offset_us();
    char text[512];
    if (sitl() && offset_us >= static_cast<int64_t>(ActuatorInput::kEchoWindow_us)) {
      std::snprintf(text, sizeof text,
                    "lockstep: PX4 SITL's answers are stamped %.1f s ahead of this session's clock: it still runs on "
                    "an earlier session's time and cannot go back, so it will not take these sensors as new. Restart "
                    "PX4 SITL together with hitl sim",
                    static_cast<double>(offset_us) * 1e-6);
      observer.on_event({Severity::Warning, text});
    } else if (!sitl() && actuators.counters().foreign_clock >= 10) {
      std::snprintf(text, sizeof text,
                    "lockstep: the board stamps its answers with its own clock, not the HIL_SENSOR's time_usec (a "
                    "PX4 board in HIL mode does; hitl target --lockstep echoes it): each answer counts, late ones "
                    "cannot be told apart");
      observer.on_event({Severity::Info, text});
    } else {
      return;
    }
    warned_clock_ahead = true;
  }

  /// Takes the operator's pause and reset requests; true while paused (the step does nothing).
  bool take_controls(Observer& observer) {
    if (const bool want = pause_wanted.load(); want != paused) {
      const double now = monotonic_s();
      char text[96];
      if (want) {
        pause_start_s = now;
        std::snprintf(text, sizeof text, "paused at %.1f s: the model holds, no sensor data is sent", sim_time_s());
      } else {
        paused_total_s += now - pause_start_s;
        resumed = true;
        std::snprintf(text, sizeof text, "resumed at %.1f s", sim_time_s());
      }
      paused = want;
      observer.on_event({Severity::Info, text});
    }
    if (reset_wanted.exchange(false)) {
      time_offset_s += model->state().time_s;  // the wire's clock carries on
      model->reset();
      sensors->reset();
      touchdowns.on_reset();
      ++resets;
      char text[96];
      std::snprintf(text, sizeof text, "reset to home at rest, motors stopped (time carries on at %.1f s)", sim_time_s());
      observer.on_event({Severity::Info, text});
    }
    return paused;
  }

  /// Once a wall-clock second, the session's own state to its clients (hitl doctor, bridge
  /// dashboards): HEARTBEAT from the simulator's sysid (STANDBY while paused) and NAMED_VALUE_*
  /// "sim_rtf" (recent real-time factor), "sim_late" (late ticks), "sim_pause" (0/1).
  void send_status_to_clients(double now_s) {
    if (!clients || now_s < next_status_wall_s) return;
    next_status_wall_s = now_s + 1.0;
    mavlink::msg::Heartbeat hb;
    hb.type = static_cast<uint8_t>(mavlink::MavType::Generic);
    hb.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Invalid);
    hb.system_status = static_cast<uint8_t>(paused ? mavlink::MavState::Standby : mavlink::MavState::Active);
    hb.mavlink_version = mavlink::kMavlinkVersion;
    broadcast_own(hb);
    const auto boot_ms = static_cast<uint32_t>((now_s - start_wall_s) * 1000.0);
    mavlink::msg::NamedValueFloat rtf;
    rtf.time_boot_ms = boot_ms;
    set_name(rtf.name, kStatusRtfName);
    rtf.value = static_cast<float>(recent_rtf);
    broadcast_own(rtf);
    mavlink::msg::NamedValueInt late;
    late.time_boot_ms = boot_ms;
    set_name(late.name, kStatusLateName);
    late.value = static_cast<int32_t>(std::min<uint64_t>(pacer ? pacer->stats().late : 0, INT32_MAX));
    broadcast_own(late);
    mavlink::msg::NamedValueInt pause;
    pause.time_boot_ms = boot_ms;
    set_name(pause.name, kStatusPauseName);
    pause.value = paused ? 1 : 0;
    broadcast_own(pause);
    send_doctor_status(boot_ms, now_s);
  }

  /// What `hitl doctor` reads beside the above (session_config.h): the requested pace, lockstep,
  /// and what the board's HIL_ACTUATOR_CONTROLS look like here (they never reach clients).
  void send_doctor_status(uint32_t boot_ms, double now_s) {
    auto named_float = [&](std::string_view name, double value) {
      mavlink::msg::NamedValueFloat m;
      m.time_boot_ms = boot_ms;
      set_name(m.name, name);
      m.value = static_cast<float>(value);
      broadcast_own(m);
    };
    auto named_int = [&](std::string_view name, int32_t value) {
      mavlink::msg::NamedValueInt m;
      m.time_boot_ms = boot_ms;
      set_name(m.name, name);
      m.value = value;
      broadcast_own(m);
    };
    double actuator_hz = 0;
    for (const auto& p : paths->stats(now_s))
      if (!p.outgoing && p.stats.since_last_s >= 0 && p.stats.since_last_s < telemetry::kStaleAfter_s) actuator_hz = p.stats.rate_hz;
    const bool heard = actuators.ever_received();
    named_float(kStatusSpeedName, config.speed);
    named_int(kStatusLockstepName, lockstep() ? 1 : 0);
    named_float(kStatusActuatorRateName, actuator_hz);
    named_int(kStatusActuatorFlagsName, heard ? actuators.last_flags() : -1);
    named_int(kStatusActuatorArmedName, heard ? (actuators.armed() ? 1 : 0) : -1);
  }

  template <class M>
  void broadcast_own(const M& message) {
    mavlink::FrameBuffer buf;
    if (const std::size_t n = truth_encoder.encode(message, buf)) clients->broadcast({buf.data(), n});
  }

  template <std::size_t N>
  static void set_name(std::array<char, N>& field, std::string_view name) {
    field.fill('\0');
    std::copy_n(name.begin(), std::min(name.size(), N), field.begin());
  }

  Status step(Observer& observer) {
    const double now_s = monotonic_s();
    drain(now_s);
    send_status_to_clients(now_s);
    serve_clients(observer);
    watch_recorder(observer);
    if (take_controls(observer)) return Ok{};
    // Lockstep waits for the answer to the last HIL_SENSOR; a step shorter than the IMU period sends none every step.
    if (!std::exchange(resumed, false) && std::exchange(sensor_sent, false)) lockstep_wait(observer);
    model->set_motor_commands(actuators.commands(unpaused_s(monotonic_s())));
    if (auto st = model->step(); !st) return st;
    const auto& state = model->state();
    touchdowns.observe(state);
    const auto frame = sensors->sample_due(state);
    if (!warned_imu_saturated && (sensors->imu().saturation().accel > 0 || sensors->imu().saturation().gyro > 0)) {
      warned_imu_saturated = true;
      observer.on_event({Severity::Warning, imu_saturated_text()});
    }
    const double sent_s = monotonic_s();
    const uint64_t t_us = mavlink::wire::s_to_us(time_offset_s + state.time_s);
    if (frame.imu || frame.mag || frame.baro) {
      send_to_stack(make_hil_sensor(frame, t_us));
      sensor_sent = true;
      if (lockstep() && frame.imu) actuators.expect_answer_to(t_us);
      paths->on_hil_sensor(frame.imu.has_value(), frame.mag.has_value(), frame.baro.has_value(), sent_s);
      if (first_sensor_wall_s < 0) first_sensor_wall_s = monotonic_s();
    }
    if (frame.gps) {
      send_to_stack(make_hil_gps(*frame.gps, t_us));
      paths->on_hil_gps(sent_s);
    }
    if (pilot) fly_pilot(state, observer);
    if (time_offset_s + state.time_s + 1e-9 >= next_heartbeat_s) {
      next_heartbeat_s += 1.0;
      mavlink::msg::Heartbeat hb;
      hb.type = static_cast<uint8_t>(mavlink::MavType::Generic);
      hb.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Invalid);
      hb.system_status = static_cast<uint8_t>(mavlink::MavState::Active);
      hb.mavlink_version = mavlink::kMavlinkVersion;
      send_to_stack(hb);
    }
    flush_to_stack();
    actuators.take_new();  // answers counted from here on belong to these sensors
    if (vio && time_offset_s + state.time_s + 1e-9 >= next_vio_s) {
      ++vio_k;
      next_vio_s = static_cast<double>(vio_k) / config.vio_rate_hz;
      send_to_vio(make_odometry(frame.truth, t_us));
      paths->on_odometry(sent_s);
    }
    if (clients && config.truth_rate_hz > 0 && time_offset_s + state.time_s + 1e-9 >= next_truth_s) {
      ++truth_k;
      next_truth_s = static_cast<double>(truth_k) / config.truth_rate_hz;
      auto odometry = make_odometry(frame.truth, t_us);
      odometry.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
      mavlink::FrameBuffer buf;
      if (const std::size_t n = truth_encoder.encode(odometry, buf)) clients->broadcast({buf.data(), n});
    }
    report_send_errors(observer);
    if (!warned_no_answer && first_sensor_wall_s >= 0 && !actuators.ever_received() &&
        monotonic_s() - first_sensor_wall_s > config.no_answer_warning_s) {
      warned_no_answer = true;
      observer.on_event({Severity::Warning, no_answer_text()});
    }
    return Ok{};
  }

  /// -t: the trajectory flight flies on ground truth, as the spec's trajectory_rc plugin does, and is
  /// scored on it.
  void fly_pilot(const model::VehicleState& state, Observer& observer) {
    const vehicle::PilotPose truth{{state.p_ENU_m.x(), state.p_ENU_m.y(), state.p_ENU_m.z()},
                                   {state.v_ENU_m_s.x(), state.v_ENU_m_s.y(), state.v_ENU_m_s.z()},
                                   frames::yaw_ENU_rad(state.q_FLU_to_ENU)};
    auto out = pilot->step(time_offset_s + state.time_s, truth, truth);
    mavlink::FrameBuffer buf;
    for (const auto& c : out.commands) forward_to_stack({buf.data(), pilot_encoder.encode(c, buf)});
    if (out.rc) forward_to_stack({buf.data(), pilot_encoder.encode(*out.rc, buf)});
    if (out.event) observer.on_event({pilot->state() == vehicle::PilotState::Failed ? Severity::Error : Severity::Info, *out.event});
  }

  std::string imu_saturated_text() const {
    const auto& imu = config.vehicle.sensors.imu;
    char text[256];
    std::snprintf(text, sizeof text,
                  "IMU at full scale (accel +-%.1f g, gyro +-%.0f deg/s, sensors.imu.*_range): a sample was clipped at "
                  "t = %.2f s, as the real sensor would; counted (imu_saturated)",
                  imu.accel_range_m_s2 / 9.80665, imu.gyro_range_rad_s * 180.0 / M_PI, sim_time_s());
    return text;
  }

  std::string no_answer_text() const {
    uint64_t delivered = 0;
    for (const auto& [id, c] : sent) delivered += c.count;
    if (send_errors > 0 && delivered == 0)
      return "no HIL_ACTUATOR_CONTROLS: nothing reached the flight stack, every send failed (" +
             std::to_string(send_errors) + " messages; " + last_send_error + ")";
    if (send_errors > 0) return no_answer_cause() + "; and " + std::to_string(send_errors) + " messages could not be sent (" + last_send_error + ")";
    return no_answer_cause();
  }

  std::string no_answer_cause() const {
    if (sitl())
      return "no HIL_ACTUATOR_CONTROLS from PX4 SITL yet; still sending. Is PX4 started with a simulator "
             "airframe (e.g. 10016 none_iris)?";
    return "no HIL_ACTUATOR_CONTROLS from " + target->to_string() + " within " +
           std::to_string(static_cast<int>(config.no_answer_warning_s)) +
           " s of the first HIL_SENSOR; still sending. Likely causes: the board's HIL instance is locked to an "
           "earlier session's port (restart PX4 on the board: voxl-px4-hitl start), HIL is not enabled (SYS_HITL must "
           "be 1), or the wrong IP (-i)";
  }

  // --- snapshot ------------------------------------------------------------------------------
  SessionSnapshot make_snapshot() const {
    SessionSnapshot s;
    const auto& st = model->state();
    s.sim_time_s = sim_time_s();
    s.wall_time_s = monotonic_s() - start_wall_s;
    s.real_time_factor = s.wall_time_s > 0 ? s.sim_time_s / s.wall_time_s : 0;
    s.recent_real_time_factor = recent_rtf;
    for (const auto& [id, c] : sent) s.sent[name_of(id)] = StreamCount{c.count, c.rate_hz};
    for (const auto& [id, c] : received) s.received[name_of(id)] = StreamCount{c.count, c.rate_hz};
    s.send_errors = send_errors;
    s.last_send_error = last_send_error;
    s.connected = sitl_tcp ? sitl_tcp->connected() : actuators.ever_received();
    if (sitl_tcp && sitl_tcp->client()) s.partner = sitl_tcp->client()->to_string();
    else if (target) s.partner = target->to_string();
    s.armed = actuators.armed();
    s.motor_commands = actuators.last_controls();
    s.rotor_speed_rad_s = st.rotor_speed_rad_s;
    s.altitude_m = st.p_ENU_m.z() - rest_altitude_m;
    s.p_NED_m = {st.p_ENU_m.y(), st.p_ENU_m.x(), -s.altitude_m};
    s.on_ground = st.on_ground;
    s.steps = st.step;
    s.late_ticks = pacer->stats().late;
    s.resyncs = pacer->stats().resyncs;
    s.max_lateness_ms = pacer->stats().max_lateness_s * 1000.0;
    s.actuator_clamped = actuators.counters().clamped;
    s.ignored_other_address = ignored_other_address;
    s.ignored_other_sysid = actuators.counters().ignored_sysid;
    s.actuator_timeouts = actuators.counters().timeouts;
    s.lockstep_waits = lockstep_waits;
    s.lockstep_fallbacks = lockstep_fallbacks;
    s.lockstep_late_answers = actuators.counters().late;
    s.lockstep_foreign_clock = actuators.counters().foreign_clock;
    s.imu_accel_saturated = sensors->imu().saturation().accel;
    s.imu_gyro_saturated = sensors->imu().saturation().gyro;
    const auto& td = touchdowns.stats();
    s.touchdowns = td.touchdowns;
    s.max_rebound_m = td.max_rebound_m;
    s.max_touchdown_speed_m_s = td.max_touchdown_speed_m_s;
    s.peak_touchdown_accel_m_s2 = td.peak_accel_m_s2;
    s.crc_errors = stack_parser->stats().crc_errors;
    s.parse_errors = stack_parser->stats().parse_errors;
    s.clients = clients ? clients->client_count() : 0;
    s.clients_refused = clients ? clients->stats().refused_datagrams : 0;
    s.client_frames_dropped = clients ? clients->stats().dropped_frames : 0;
    s.routed_to_board = routed_to_board;
    s.routed_to_clients = routed_to_clients;
    if (pilot) {
      s.trajectory_state = vehicle::to_string(pilot->state());
      s.trajectory_failure = pilot->failure();
      const auto t = pilot->tracking();
      s.trajectory_samples = t.samples;
      s.trajectory_rms_m = t.rms_m;
      s.trajectory_max_m = t.max_m;
    }
    s.actuator_flags = actuators.last_flags();
    s.actuator_mode = actuators.last_mode();
    s.paths = paths->stats(monotonic_s());
    s.paused = paused;
    s.resets = resets;
    s.speed = config.speed;
    s.lockstep = lockstep();
    if (recorder) s.record_error = recorder->error();
    return s;
  }

  void publish() {
    auto s = make_snapshot();
    std::lock_guard<std::mutex> lock(snapshot_mutex);
    published = std::move(s);
  }

  void roll_window() {
    const double now = monotonic_s();
    const double dt = now - window_start_wall_s;
    if (dt <= 0) return;
    for (auto* m : {&sent, &received})
      for (auto& [id, c] : *m) {
        c.rate_hz = static_cast<double>(c.window) / dt;
        c.window = 0;
      }
    recent_rtf = (sim_time_s() - window_start_sim_s) / dt;
    paths->roll(now, config.speed > 0 ? config.speed : recent_rtf);
    window_start_wall_s = now;
    window_start_sim_s = sim_time_s();
  }
};

Expected<std::unique_ptr<Session>> Session::create(const SessionConfig& config) {
  auto impl = std::make_unique<Impl>();
  impl->config = config;
  model::VehicleConfig vehicle = config.noise ? config.vehicle : model::with_noise_disabled(config.vehicle);
  auto mc = model::Multicopter::create(vehicle, config.world, config.seed);
  if (!mc) return mc.error();
  impl->model = std::move(mc.value());
  impl->sensors.emplace(vehicle, config.world, config.seed);
  impl->rest_altitude_m = impl->model->state().p_ENU_m.z();
  impl->encoder = mavlink::FrameEncoder(config.sysid, config.compid, config.protocol);
  impl->vio_encoder = mavlink::FrameEncoder(config.sysid, kVioComponentId, config.protocol);
  impl->truth_encoder = mavlink::FrameEncoder(config.sysid, config.compid, config.protocol);
  impl->stack_parser.emplace(impl->messages);
  impl->client_parser.emplace(impl->messages);
  impl->actuators = ActuatorInput(config.actuator_timeout_s);
  if (!(config.vio_rate_hz > 0)) return Error{"--vio-rate must be > 0"};
  if (!(config.truth_rate_hz >= 0)) return Error{"--truth-rate must be >= 0 (0: no truth to clients)"};
  if (!(config.speed >= 0)) return Error{"--speed must be >= 0 (0: as fast as possible)"};
  if (!std::isfinite(config.actuator_timeout_s) || !(config.actuator_timeout_s > 0))
    return Error{"--actuator-timeout must be a finite number > 0"};
  if (!std::isfinite(config.lockstep_timeout_s) || !(config.lockstep_timeout_s > 0))
    return Error{"--lockstep-timeout must be a finite number > 0"};
  if (auto st = check_step_divides_sensor_periods(config.world.physics.step_s, vehicle); !st) return st.error();

  if (config.link == FlightStackLink::SitlTcp) {
    auto server = net::TcpServer::listen(config.bind_address, config.sitl_port, "--px4-sitl");
    if (!server) return server.error();
    impl->sitl_tcp.emplace(std::move(server.value()));
  } else {
    const uint16_t remote = config.link == FlightStackLink::SitlUdp ? config.sitl_port : config.hil_port;
    auto target = net::SocketAddress::resolve(config.target_ip, remote);
    if (!target) return Error{"--target-ip: " + target.error().message};
    impl->target = *target;
    net::UdpEndpoint::Config ec;
    ec.name = "HIL link (--local-port)";
    ec.bind_address = config.bind_address;
    ec.bind_port = config.local_port;
    ec.peer = *target;
    ec.policy = net::PartnerPolicy::Fixed;
    auto ep = net::UdpEndpoint::open(ec);
    if (!ep) return ep.error();
    impl->hil_udp.emplace(std::move(ep.value()));
  }
  if (config.vio) {
    auto vio_target = net::SocketAddress::resolve(config.vio_ip.empty() ? config.target_ip : config.vio_ip, config.vio_port);
    if (!vio_target) return Error{"--vio-ip: " + vio_target.error().message};
    net::UdpEndpoint::Config ec;
    ec.name = "VIO link";
    ec.bind_address = config.bind_address;
    ec.bind_port = 0;
    ec.peer = *vio_target;
    ec.policy = net::PartnerPolicy::Fixed;
    auto ep = net::UdpEndpoint::open(ec);
    if (!ep) return ep.error();
    impl->vio.emplace(std::move(ep.value()));
  }
  std::vector<net::SocketAddress> fixed;
  if (!config.gcs.empty()) {
    auto gcs = net::SocketAddress::parse(config.gcs, "--gcs");
    if (!gcs) return gcs.error();
    fixed.push_back(*gcs);
  }
  if (config.clients_port != 0 || !fixed.empty()) {
    auto cp = net::ClientPort::open(config.clients_bind, config.clients_port, fixed);
    if (!cp) return Error{cp.error().message + " (is another hitl sim or hitl bridge running? --clients 0 disables)"};
    impl->clients.emplace(std::move(cp.value()));
    Impl* i = impl.get();
    impl->board_link = impl->router.add_link("board", [i](std::span<const uint8_t> bytes, const auto&) { i->forward_to_stack(bytes); });
    impl->clients_link = impl->router.add_link(
        "clients",
        [i](std::span<const uint8_t> bytes, const std::optional<net::SocketAddress>& except) {
          i->clients->broadcast(bytes, except);
          ++i->routed_to_clients;
        },
        /*hub=*/true);
  }
  if (config.trajectory) {
    if (config.link == FlightStackLink::SitlTcp)
      return Error{"-t: PX4 SITL takes only HIL messages on its simulator link; fly the trajectory with "
                   "`hitl fly trajectory` against its GCS port instead"};
    vehicle::PilotConfig pc;
    pc.home_alt_msl_m = config.world.home.alt_m;
    pc.mode = config.trajectory_mode;
    impl->pilot.emplace(*config.trajectory, pc);
  }
  if (!config.record_path.empty()) {
    auto w = mavlink::TlogWriter::open(config.record_path);
    if (!w) return w.error();
    impl->recorder.emplace(std::move(w.value()));
  }
  impl->pacer.emplace(config.world.physics.step_s, config.speed);  // one step of simulated time per tick
  impl->paths.emplace(config);
  return std::unique_ptr<Session>(new Session(std::move(impl)));
}

Session::Session(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Session::~Session() = default;

std::string Session::describe() const {
  const auto& c = impl_->config;
  std::string out;
  if (impl_->sitl_tcp) out = "serving PX4 SITL on TCP " + impl_->sitl_tcp->local_address().to_string() + " (lockstep)";
  else
    out = "HIL_SENSOR/HIL_GPS to " + impl_->target->to_string() + " from " + impl_->hil_udp->local_address().to_string() +
          (c.lockstep ? " (lockstep)" : "");
  if (impl_->vio)
    out += ", ODOMETRY to " + impl_->vio->partner()->to_string() + " at " + std::to_string(static_cast<int>(c.vio_rate_hz)) + " Hz";
  if (impl_->clients && impl_->clients->local_address())
    out += ", clients on " + impl_->clients->local_address()->to_string();
  if (!c.gcs.empty()) out += ", GCS " + c.gcs;
  char speed[64];
  std::snprintf(speed, sizeof speed, c.speed > 0 ? ", speed %gx" : ", as fast as possible", c.speed);
  return out + speed;
}

Expected<Session::EndReason> Session::run(const std::atomic<bool>& stop, Observer& observer) {
  Impl& s = *impl_;
  if (!s.config.noise)
    observer.on_event({Severity::Warning,
                       "--no-noise: PX4 marks a sensor stale after ~100 identical values, so a flight stack on the "
                       "other end will refuse to arm; use it for tests only"});
  if (s.config.realtime) {
    sched_param sp{};
    sp.sched_priority = 50;
    const bool fifo = sched_setscheduler(0, SCHED_FIFO, &sp) == 0;
    const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
    observer.on_event({fifo && locked ? Severity::Info : Severity::Warning,
                       std::string("--realtime: SCHED_FIFO ") + (fifo ? "granted" : "not permitted") + ", mlockall " +
                           (locked ? "granted" : "not permitted") +
                           (fifo && locked ? "" : " (run as root or grant CAP_SYS_NICE and CAP_IPC_LOCK)")});
  }
  if (s.sitl_tcp) {
    observer.on_event({Severity::Info, "waiting for PX4 SITL to connect to TCP " + s.sitl_tcp->local_address().to_string() +
                                           "; start PX4 now, in its build tree: PX4_SYS_AUTOSTART=10016 "
                                           "PX4_SIM_MODEL=none_iris build/px4_sitl_default/bin/px4 (docs/sim.md adds the "
                                           "x500 geometry as PX4_PARAM_ variables)"});
    const double wait_start_s = monotonic_s();
    double next_note_s = wait_start_s + 10.0;
    while (!s.sitl_tcp->accept_client(200)) {
      if (stop.load()) return EndReason::Stopped;
      if (monotonic_s() >= next_note_s) {
        next_note_s += 10.0;
        observer.on_event({Severity::Info, "still waiting for PX4 SITL on TCP " + std::to_string(s.sitl_tcp->local_address().port()) +
                                               " (" + std::to_string(static_cast<int>(monotonic_s() - wait_start_s)) + " s)"});
      }
    }
    observer.on_event({Severity::Info, "PX4 SITL connected from " + s.sitl_tcp->client()->to_string()});
  }
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
    s.check_clock_ahead(observer);
    if (s.lockstep_dead(observer)) {
      reason = EndReason::FlightStackGone;
      break;
    }
    if (s.stack_gone) {
      observer.on_event({Severity::Error, "PX4 SITL disconnected; PX4 never reconnects to a simulator, so this session "
                                          "ends (restart PX4 and hitl sim together)"});
      reason = EndReason::FlightStackGone;
      break;
    }
    const double now = monotonic_s();
    if (now >= next_publish_s) {
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
  if (s.recorder) s.recorder->flush();
  s.watch_recorder(observer);
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
