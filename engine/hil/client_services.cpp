#include "engine/hil/client_services.h"

#include <algorithm>
#include <cstdio>

#include "base/common/clock.h"
#include "engine/hil/sensor_messages.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/severity.h"
#include "base/mavlink/text_field.h"
#include "engine/net/link_spec.h"
#include "engine/net/open_link.h"

namespace hitl::hil {

Expected<std::unique_ptr<ClientServices>> ClientServices::open(const SessionConfig& config,
                                                               const mavlink::MessageSet& messages, StackLink& stack,
                                                               Traffic& traffic, Recording& recording) {
  auto s = std::unique_ptr<ClientServices>(new ClientServices(config, messages, stack, traffic, recording));
  if (config.vio) {
    net::LinkSpec vio;  // udp:VIO_IP:VIO_PORT from an ephemeral port
    vio.kind = net::LinkSpec::Kind::Udp;
    vio.host = config.vio_ip.empty() ? config.target_ip : config.vio_ip;
    vio.port = config.vio_port;
    net::LinkSettings settings;
    settings.name = "VIO link";
    settings.host_what = "the VIO address";
    settings.bind_address = config.bind_address;
    auto link = net::open_link(vio, settings);
    if (!link) return link.error();
    s->vio_ = std::move(link.value());
  }
  std::vector<net::SocketAddress> fixed;
  if (!config.gcs.empty()) {
    auto spec = net::parse_udp_peer(config.gcs, "the ground station is a UDP peer of the client port");
    if (!spec) return spec.error().prefixed("--gcs ");
    auto gcs = net::SocketAddress::resolve(spec->host, spec->port);
    if (!gcs) return gcs.error().prefixed("--gcs: ");
    fixed.push_back(*gcs);
  }
  if (config.clients_port != 0 || !fixed.empty()) {
    auto cp = net::ClientPort::open(config.clients_bind, config.clients_port, fixed);
    if (!cp) return cp.error().suffixed(" (is another hitl sim or hitl bridge running? --clients 0 disables)");
    s->clients_.emplace(std::move(cp.value()));
    ClientServices* self = s.get();
    s->board_link_ = s->router_.add_link("board", [self](std::span<const uint8_t> bytes, const auto&) { self->stack_.forward(bytes); });
    s->clients_link_ = s->router_.add_link(
        "clients",
        [self](std::span<const uint8_t> bytes, const router::Delivery& to) {
          self->clients_->broadcast(bytes, to.except, to.only);
          ++self->routed_to_clients_;
        },
        /*hub=*/true);
  }
  return s;
}

ClientServices::ClientServices(const SessionConfig& config, const mavlink::MessageSet& messages, StackLink& stack,
                               Traffic& traffic, Recording& recording)
    : config_(config),
      stack_(stack),
      traffic_(traffic),
      recording_(recording),
      client_parser_(messages),
      own_encoder_(config.sysid, config.compid, config.protocol),
      vio_encoder_(config.sysid, kVioComponentId, config.protocol),
      vio_faults_(config.seed, "vio-link") {}

void ClientServices::drain(double now_s) {
  if (!clients_) return;
  clients_->receive_some(kMaxDatagramsPerDrain, [&](const net::Datagram& d) {
    client_parser_.parse_datagram(d.bytes, [&](const mavlink::Frame& f) {
      if (is_hil_message(f.msgid)) return;
      router_.route(f, clients_link_, now_s, d.from);  // to the board, and to the other clients
    });
  });
}

void ClientServices::route_from_stack(const mavlink::Frame& frame, double now_s) {
  if (clients_ && !is_hil_message(frame.msgid)) router_.route(frame, board_link_, now_s);
}

void ClientServices::serve(EventSink& events) {
  if (!clients_) return;
  clients_->pump();
  const auto& st = clients_->stats();
  if (st.refused_datagrams > 0 && !warned_full_) {
    warned_full_ = true;
    events.on_event({Severity::Warning, "client port: " + std::to_string(clients_->limits().max_clients) +
                                            " clients already; datagrams from further senders are dropped (counted: "
                                            "clients_refused) until one goes silent for " +
                                            std::to_string(net::ClientPort::kClientTimeout.count()) + " s"});
  }
  if (st.dropped_frames > 0 && !warned_dropped_) {
    warned_dropped_ = true;
    events.on_event({Severity::Warning, "client port: more to send than " +
                                            std::to_string(clients_->limits().max_datagrams_out) +
                                            " datagrams per step; frames to clients dropped (counted: "
                                            "client_frames_dropped)"});
  }
}

template <class M>
void ClientServices::broadcast_own(const M& message) {
  mavlink::FrameBuffer buf;
  const std::size_t n = own_encoder_.encode(message, buf);
  if (n == 0) return;
  recording_.record({buf.data(), n});
  if (clients_) clients_->broadcast({buf.data(), n});
}

void ClientServices::announce(Severity severity, std::string_view text) {
  for (const auto& st : statustext_chunker_.split(static_cast<uint8_t>(mavlink::mav_severity(severity)), text))
    broadcast_own(st);
}

/// HEARTBEAT from the simulator's sysid (STANDBY while paused) and NAMED_VALUE_* "sim_rtf" (recent
/// real-time factor), "sim_late" (late ticks), "sim_pause" (0/1), then what hitl doctor reads.
void ClientServices::send_status(double now_s, double sim_s, double start_wall_s, const SessionStatus& status) {
  if (!status_due(now_s, sim_s)) return;
  const auto boot_ms = static_cast<uint32_t>((now_s - start_wall_s) * 1000.0);
  if (now_s < next_status_wall_s_) return send_loop_latency(boot_ms, sim_s, status);  // a simulated second only
  next_status_wall_s_ = now_s + 1.0;
  broadcast_own(mavlink::simulator_heartbeat(status.paused ? mavlink::MavState::Standby : mavlink::MavState::Active));
  mavlink::msg::NamedValueFloat rtf;
  rtf.time_boot_ms = boot_ms;
  mavlink::set_text(rtf.name, kStatusRtfName);
  rtf.value = static_cast<float>(status.recent_real_time_factor);
  broadcast_own(rtf);
  mavlink::msg::NamedValueInt late;
  late.time_boot_ms = boot_ms;
  mavlink::set_text(late.name, kStatusLateName);
  late.value = static_cast<int32_t>(std::min<uint64_t>(status.late_ticks, INT32_MAX));
  broadcast_own(late);
  mavlink::msg::NamedValueInt pause;
  pause.time_boot_ms = boot_ms;
  mavlink::set_text(pause.name, kStatusPauseName);
  pause.value = status.paused ? 1 : 0;
  broadcast_own(pause);
  send_doctor_status(boot_ms, status);
  send_loop_latency(boot_ms, sim_s, status);
}

/// What `hitl doctor` reads beside the above (session_config.h): the requested pace, lockstep, and
/// what the board's HIL_ACTUATOR_CONTROLS look like here (they never reach clients).
void ClientServices::send_doctor_status(uint32_t boot_ms, const SessionStatus& status) {
  auto named_float = [&](std::string_view name, double value) {
    mavlink::msg::NamedValueFloat m;
    m.time_boot_ms = boot_ms;
    mavlink::set_text(m.name, name);
    m.value = static_cast<float>(value);
    broadcast_own(m);
  };
  auto named_int = [&](std::string_view name, int32_t value) {
    mavlink::msg::NamedValueInt m;
    m.time_boot_ms = boot_ms;
    mavlink::set_text(m.name, name);
    m.value = value;
    broadcast_own(m);
  };
  const auto& actuators = stack_.actuators();
  const bool heard = actuators.ever_received();
  named_float(kStatusSpeedName, config_.speed);
  named_int(kStatusLockstepName, stack_.lockstep() ? 1 : 0);
  named_float(kStatusActuatorRateName, status.actuator_rate_hz);
  named_int(kStatusActuatorFlagsName, heard ? actuators.last_flags() : -1);
  named_int(kStatusActuatorArmedName, heard ? (actuators.armed() ? 1 : 0) : -1);
  if (status.px4_instance) named_int(kStatusPx4InstanceName, *status.px4_instance);
}

/// NAMED_VALUE_INT sim_lat50, sim_lat99 (hitl doctor's), sim_latmx: us so far, -1 before an answer.
void ClientServices::send_loop_latency(uint32_t boot_ms, double sim_s, const SessionStatus& status) {
  next_latency_sim_s_ = sim_s + 1.0;
  auto named_int = [&](std::string_view name, const std::optional<double>& us) {
    mavlink::msg::NamedValueInt m;
    m.time_boot_ms = boot_ms;
    mavlink::set_text(m.name, name);
    m.value = us ? static_cast<int32_t>(std::min(*us, 2e9)) : -1;
    broadcast_own(m);
  };
  named_int(kStatusLoopLatencyP50Name, status.loop_latency_p50_us);
  named_int(kStatusLoopLatencyP99Name, status.loop_latency_p99_us);
  named_int(kStatusLoopLatencyMaxName, status.loop_latency_max_us);
}

void ClientServices::send_truth_if_due(const sensors::GroundTruth& truth, uint64_t time_usec, double sim_s) {
  if ((!clients_ && !recording_.active()) || !(config_.truth_rate_hz > 0) || sim_s + 1e-9 < next_truth_s_) return;
  ++truth_k_;
  next_truth_s_ = static_cast<double>(truth_k_) / config_.truth_rate_hz;
  auto odometry = make_odometry(truth, time_usec);
  odometry.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
  broadcast_own(odometry);
}

bool ClientServices::send_vio_if_due(const sensors::GroundTruth& truth, uint64_t time_usec, double sim_s,
                                     const faults::ActiveFaults& faults) {
  if (!vio_ || sim_s + 1e-9 < next_vio_s_) return false;
  ++vio_k_;
  next_vio_s_ = static_cast<double>(vio_k_) / config_.vio_rate_hz;
  if (faults.vio_loss) return false;
  sensors::GroundTruth seen = truth;
  seen.p_NED_m += faults.vio_offset_NED_m;
  auto odometry = make_odometry(seen, time_usec);
  odometry.reset_counter = static_cast<uint8_t>(odometry.reset_counter + faults.vio_resets);  // wraps as on the wire
  if (faults.vio_quality) odometry.quality = static_cast<int8_t>(*faults.vio_quality);
  mavlink::FrameBuffer buf;
  const std::size_t n = vio_encoder_.encode(odometry, buf);
  if (n == 0) return true;
  if (vio_faults_.holding()) {  // vio-drop, vio-delay, ...: it leaves (or not) later, recorded then
    vio_faults_.hold({buf.data(), n}, mavlink::msg::Odometry::kId);
    vio_faults_.close_datagram(monotonic_s());
    release_vio_delayed(monotonic_s());
    return true;
  }
  send_vio_frame({buf.data(), n}, true);
  return true;
}

void ClientServices::send_vio_frame(std::span<const uint8_t> frame, bool counted) {
  recording_.record(frame);
  if (auto st = vio_->send(frame); st) {
    if (counted) traffic_.count_sent(mavlink::msg::Odometry::kId, 1);
  } else {
    traffic_.count_failed(1, st.error().message);
  }
}

void ClientServices::release_vio_delayed(double now_s) {
  if (!vio_) return;
  vio_faults_.release_due(now_s, [&](LinkFaults::Datagram& d) {
    for (const auto& f : d.frames) send_vio_frame(f, !d.counts.empty());
  });
}

std::vector<std::string> ClientServices::take_send_errors() { return vio_ ? vio_->take_send_errors() : std::vector<std::string>{}; }

std::string ClientServices::describe() const {
  std::string out;
  if (vio_)
    out += ", ODOMETRY to " + vio_->peer()->to_string() + " at " + std::to_string(static_cast<int>(config_.vio_rate_hz)) + " Hz";
  if (clients_ && clients_->local_address()) out += ", clients on " + clients_->local_address()->to_string();
  if (!config_.gcs.empty()) out += ", GCS " + config_.gcs;
  return out;
}

}  // namespace hitl::hil
