#include "engine/vehicle/vehicle_link.h"

#include "base/common/clock.h"
#include <chrono>

#include "base/mavlink/enums.h"
#include "base/mavlink/heartbeat.h"
#include "engine/net/open_link.h"

namespace hitl::vehicle {
namespace {

/// The direct UDP link auto takes: from `local_port` to `peer`, which never changes.
Expected<std::unique_ptr<net::Link>> open_udp_to(const net::SocketAddress& peer, const std::string& bind, uint16_t local_port,
                                                 const std::string& name) {
  net::LinkSpec spec;
  spec.kind = net::LinkSpec::Kind::Udp;
  spec.host = peer.host();
  spec.port = peer.port();
  net::LinkSettings settings;
  settings.name = name;
  settings.bind_address = bind;
  settings.local_port = local_port;
  return net::open_link(spec, settings);
}

}  // namespace

VehicleLink::VehicleLink(std::unique_ptr<net::Link> link, const LinkOptions& options, std::string description)
    : link_(std::move(link)),
      messages_(mavlink::MessageSet::compiled()),
      parser_(messages_),
      encoder_(options.own_sysid, options.own_compid),
      options_(options),
      description_(std::move(description)) {}

void VehicleLink::heartbeat() {
  send(mavlink::gcs_heartbeat());
  last_heartbeat_s_ = monotonic_s();
}

void VehicleLink::send_bytes(std::span<const uint8_t> bytes) {
  if (!link_->connected()) return;  // a TCP server that went away: nothing more to send
  if (record_) record_(bytes);
  // The first refusal, errno and the likely fix; a stream that broke is closed, not refused.
  if (auto st = link_->send(bytes); !st && link_->connected() && send_error_.empty()) send_error_ = st.error().message;
}

bool VehicleLink::wait(double timeout_s, const FrameHandler& handler) {
  const double end = monotonic_s() + timeout_s;
  bool done = false;
  auto on_frame = [&](const mavlink::Frame& f) {
    if (done) return;
    if (record_) record_(f.bytes());
    if (f.desc == nullptr) return;
    if (sysid_ != 0 && f.sysid != sysid_) {
      if (other_systems_) other_systems_(f);
      return;
    }
    done = handler(f);
  };
  for (;;) {
    if (!link_->connected()) return false;  // a stream does not come back: the caller's wait ends
    if (options_.stop != nullptr && options_.stop->load()) return false;
    if (monotonic_s() - last_heartbeat_s_ >= 1.0) heartbeat();
    // Nothing could be sent and nothing came: no answer will come, so do not wait for one.
    if (const auto& st = link_->stats(); st.datagrams_out == 0 && st.send_errors > 0 && st.datagrams_in == 0) return false;
    const double left = end - monotonic_s();
    if (left <= 0) return false;
    const int wait_ms = static_cast<int>(std::min(left, 0.2) * 1000) + 1;
    if (!link_->wait_readable(wait_ms)) continue;
    // One read at a time: what comes after the frame that ends the wait stays for the next wait.
    while (!done && link_->drain(parser_, on_frame, 1) > 0) {
    }
    if (done) return true;
  }
}

bool VehicleLink::discover(double timeout_s) {
  return wait(timeout_s, [&](const mavlink::Frame& f) {
    if (!f.is<mavlink::msg::Heartbeat>()) return false;
    const auto hb = f.as<mavlink::msg::Heartbeat>();
    if (hb.autopilot == static_cast<uint8_t>(mavlink::MavAutopilot::Invalid)) return false;  // a GCS or the simulator
    if (options_.sysid && f.sysid != *options_.sysid) return false;
    sysid_ = f.sysid;
    compid_ = f.compid;
    return true;
  });
}

Expected<std::unique_ptr<VehicleLink>> VehicleLink::connect(const LinkOptions& options) {
  const std::string& spec = options.connect;
  auto make = [&](std::unique_ptr<net::Link> l, std::string description) {
    return std::unique_ptr<VehicleLink>(new VehicleLink(std::move(l), options, std::move(description)));
  };
  std::unique_ptr<VehicleLink> link;
  if (spec == "auto") {
    // A running session first: it routes to the board, whose instance answers only the session.
    auto session = net::SocketAddress::resolve("127.0.0.1", options.session_port);
    if (session && net::udp_listener_may_be_at(*session)) {
      auto ep = open_udp_to(*session, "127.0.0.1", 0, "session client");
      if (ep) {
        link = make(std::move(ep.value()), "through the session on 127.0.0.1:" + std::to_string(options.session_port));
        if (link->discover(std::min(options.timeout_s, 1.5))) return link;
      }
    }
    auto board = net::resolve_board_address(options.target_ip, options.gcs_port);
    if (!board) return board.error();
    auto ep = open_udp_to(*board, "0.0.0.0", options.local_port, "--local-port");
    if (!ep)
      // Failed, not Unavailable: the port is taken by another command talking to the board (the
      // board is owned, as "no board answered"), and hitl params/arm/... exit 1 for it.
      return Error::failed("local port " + std::to_string(options.local_port) +
                   " is busy: another hitl command is talking to the board; run `hitl bridge` and let every command "
                   "go through it (" + ep.error().message + ")");
    link = make(std::move(ep.value()), "direct to " + board->to_string() + " from port " + std::to_string(options.local_port));
  } else {
    // One grammar (engine/net/link_spec.h); what each kind means for a command's link:
    // udp: from the fixed --local-port; tcp: no reconnect (a lost connection ends the command);
    // tcpin: one client (the autopilot's side connects), waited for within --timeout.
    auto parsed = net::parse_link_spec(spec);
    if (!parsed) return Error::input("--connect: " + parsed.error().message + " (or auto)");
    net::LinkSettings settings;
    settings.name = parsed->kind == net::LinkSpec::Kind::Udp ? "--local-port" : "--connect " + parsed->text;
    settings.host_what = "--connect";
    settings.local_port = options.local_port;
    settings.connect_timeout_ms = static_cast<int>(options.timeout_s * 1000);
    auto opened = net::open_link(*parsed, settings);
    if (!opened) return opened.error();
    std::string description;
    const auto local = opened.value()->local_address();
    const std::string port_text = local ? std::to_string(local->port()) : std::to_string(parsed->port);
    switch (parsed->kind) {
      case net::LinkSpec::Kind::Udp:
        description = "to " + opened.value()->peer()->to_string() + " from port " + std::to_string(options.local_port);
        break;
      case net::LinkSpec::Kind::UdpIn: description = "listening on UDP " + port_text; break;
      case net::LinkSpec::Kind::Tcp: description = "over TCP to " + opened.value()->peer()->to_string(); break;
      case net::LinkSpec::Kind::TcpIn: description = "serving TCP " + port_text; break;
    }
    if (parsed->kind == net::LinkSpec::Kind::TcpIn && !opened.value()->wait_connected(static_cast<int>(options.timeout_s * 1000)))
      return Error::failed("no autopilot connected to TCP " + port_text + " (--connect " + parsed->text + ") within " +
                           std::to_string(static_cast<int>(options.timeout_s)) + " s");
    link = make(std::move(opened.value()), description);
  }
  const bool found = link->discover(options.timeout_s);
  if (!found && !link->send_error_.empty()) return Error::failed("no autopilot " + link->description() + ": " + link->send_error_);
  if (!found)
    return Error::failed("no autopilot HEARTBEAT " + link->description() + " within " + std::to_string(static_cast<int>(options.timeout_s)) +
                         " s. Is the board up (or `hitl target` running)? A PX4 MAVLink instance answers only the first address "
                         "and port it heard: if another tool talked to it first from another port, restart PX4 on the board "
                         "(voxl-px4-hitl start) or talk through `hitl bridge`");
  return link;
}

}  // namespace hitl::vehicle
