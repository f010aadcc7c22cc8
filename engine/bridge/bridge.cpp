#include "engine/bridge/bridge.h"

#include <poll.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <memory>

#include "base/common/clock.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/sequence_tracker.h"
#include "engine/net/client_port.h"
#include "engine/net/link.h"
#include "engine/net/open_link.h"
#include "engine/net/udp_link.h"
#include "engine/router/router.h"

namespace hitl::bridge {
namespace {

namespace msg = mavlink::msg;
constexpr double kReconnectPeriod_s = 2.0;
constexpr int kTcpConnectTimeout_ms = 500;
constexpr std::size_t kMaxTcpClients = 16;  ///< per --endpoint tcpin: (ground station tools)
constexpr std::size_t kTimesyncRemembered = 8;
constexpr std::size_t kMaxClientDatagramsPerDrain = 64;
constexpr std::size_t kMaxDatagramsPerDrain = 256;  ///< per link and wake-up: a flood cannot hold the loop
/// The board is read only while the clients' queue has room for this many more frames (a
/// datagram's worth), so what is taken in is sent, and a board faster than the clients waits in
/// the kernel's receive buffer, whose overflow is counted there (kernel_rx_drops).
constexpr std::size_t kRoomForADatagram = 128;
constexpr int kBoardReceiveBuffer_bytes = 1 << 20;  ///< as before: a larger one only adds latency under overload
/// The client port sized for a 100-client fan-out of a flat-out board stream.
constexpr net::ClientPortLimits kClientLimits{.max_clients = 128,
                                              .max_datagrams_out = 4096,
                                              .max_queued_frames = 2048,
                                              .send_buffer_bytes = 4 << 20,
                                              .receive_buffer_bytes = 1 << 20};

std::string source_key(uint8_t sysid, uint8_t compid) { return std::to_string(sysid) + "/" + std::to_string(compid); }

/// One --endpoint: its link, its parser and its place in the router.
struct Endpoint {
  net::LinkSpec spec;
  std::unique_ptr<net::Link> link;
  std::unique_ptr<mavlink::FrameParser> parser;
  uint64_t parser_connects = 0;  ///< a TCP reconnect starts a fresh parser
  router::LinkId route = 0;
};

/// The link an --endpoint names (engine/net/open_link.h): udp:HOST:PORT hears its peer only;
/// udpin: answers whoever spoke last; tcp: reconnects every kReconnectPeriod_s; tcpin: takes up to
/// kMaxTcpClients ground station tools.
Expected<std::unique_ptr<net::Link>> open_endpoint_link(const net::LinkSpec& spec) {
  net::LinkSettings settings;
  settings.name = "--endpoint " + spec.text;
  settings.hear_peer_only = true;
  settings.connect_timeout_ms = kTcpConnectTimeout_ms;
  settings.reconnect_period_s = kReconnectPeriod_s;
  settings.max_clients = kMaxTcpClients;
  return net::open_link(spec, settings);
}

class Bridge {
 public:
  Bridge(const BridgeConfig& config, BridgeObserver& observer)
      : config_(config), observer_(observer), router_(config.dedup_window_s), board_parser_(messages_),
        clients_parser_(messages_), own_(kBridgeSystemId, kBridgeComponentId) {}

  Status open() {
    auto target = net::resolve_board_address(config_.board_ip, config_.board_port);
    if (!target) return target.error();
    board_address_ = *target;
    net::UdpLink::Config c;
    c.endpoint.bind_port = config_.local_port;
    c.endpoint.peer = *target;
    c.endpoint.policy = net::PartnerPolicy::Fixed;
    c.endpoint.name = "the board link's local port (--local-port)";
    c.hear_peer_only = true;  // the board answers from its own port; anyone else is not the board
    c.endpoint.receive_buffer_bytes = kBoardReceiveBuffer_bytes;
    auto ep = net::UdpLink::open(c);
    if (!ep) return ep.error().suffixed(" (a hitl sim, another hitl bridge or a direct command owns it?)");
    board_buffers_ = ep.value()->buffer_sizes();
    board_ = std::move(ep.value());
    board_link_ = router_.add_link("board", [this](std::span<const uint8_t> bytes, const auto&) { (void)board_->send(bytes); });

    if (config_.clients_port != 0) {
      auto cp = net::ClientPort::open(config_.clients_bind, config_.clients_port, {}, kClientLimits);
      if (!cp) return cp.error().suffixed(" (is a hitl sim or another hitl bridge running? --clients 0 disables)");
      clients_.emplace(std::move(cp.value()));
      clients_link_ = router_.add_link(
          "clients", [this](std::span<const uint8_t> bytes, const router::Delivery& to) {
            clients_->broadcast(bytes, to.except, to.only);
          },
          /*hub=*/true);
    }
    for (const auto& spec : config_.endpoints) {
      auto e = std::make_unique<Endpoint>();
      e->spec = spec;
      e->parser = std::make_unique<mavlink::FrameParser>(messages_);
      auto link = open_endpoint_link(spec);
      if (!link) return link.error();
      e->link = std::move(link.value());
      net::Link* raw = e->link.get();
      e->route = router_.add_link(
          spec.text,
          [raw](std::span<const uint8_t> bytes, const router::Delivery& to) {
            // udpin: nobody to answer until someone spoke; tcp, tcpin: nothing while disconnected
            if (raw->connected() && raw->peer()) (void)raw->send_to_peers(bytes, to.except, to.only);
          },
          /*hub=*/raw->hub());
      endpoints_.push_back(std::move(e));
    }
    return Ok{};
  }

  std::string describe() const {
    std::string out = "bridge: board " + board_address_->to_string() + " from local port " + std::to_string(config_.local_port);
    if (clients_) out += ", clients on " + clients_->local_address()->to_string();
    for (const auto& e : endpoints_) out += ", " + e->spec.text;
    return out;
  }

  /// The socket buffers the kernel granted, against what was asked (net.core.rmem_max / wmem_max cap them).
  std::string describe_buffers() const {
    const auto granted = [](int asked, int got, const char* cap) {
      // Linux doubles what it is asked for (its bookkeeping); less than that: the sysctl capped it.
      std::string text = std::to_string(got) + " B";
      if (got < 2 * asked) text += " (asked " + std::to_string(asked) + " B; " + cap + " caps it)";
      return text;
    };
    std::string out = "socket buffers granted: board receive " + granted(kBoardReceiveBuffer_bytes, board_buffers_.receive_bytes, "net.core.rmem_max");
    if (clients_) {
      const auto b = clients_->buffer_sizes();
      out += ", clients send " + granted(kClientLimits.send_buffer_bytes, b.send_bytes, "net.core.wmem_max") + ", clients receive " +
             granted(kClientLimits.receive_buffer_bytes, b.receive_bytes, "net.core.rmem_max");
    }
    return out;
  }

  Status run(const std::atomic<bool>& stop) {
    observer_.on_event(describe_buffers(), Severity::Info);
    start_s_ = monotonic_s();
    next_tick_s_ = start_s_;
    while (!stop.load()) {
      const double now = monotonic_s();
      if (config_.duration_s > 0 && now - start_s_ >= config_.duration_s) break;
      if (now >= next_tick_s_) {
        next_tick_s_ += config_.health_period_s;
        if (next_tick_s_ < now) next_tick_s_ = now + config_.health_period_s;
        tick(now);
      }
      for (auto& e : endpoints_) e->link->maintain(now);
      say_link_events();
      wait_readable(std::min(50.0, (next_tick_s_ - monotonic_s()) * 1000.0));
      drain(monotonic_s());
      if (clients_) clients_->pump();
      watch_board(monotonic_s());
    }
    return Ok{};
  }

 private:
  void wait_readable(double timeout_ms) {
    std::vector<pollfd> fds;
    // A board faster than the clients waits in its socket while their queue is full.
    if (!clients_ || clients_->own_room() >= kRoomForADatagram) fds.push_back({board_->fd(), POLLIN, 0});
    if (clients_) fds.push_back({clients_->fd(), static_cast<short>(POLLIN | (clients_->wants_writable() ? POLLOUT : 0)), 0});
    for (const auto& e : endpoints_)
      if (e->link->fd() >= 0) fds.push_back({e->link->fd(), POLLIN, 0});
    int ms = std::max(0, static_cast<int>(timeout_ms));
    // The client port's send bound left some for later: go on at once (unless its buffer is full).
    if (clients_ && clients_->queued_frames() > 0 && !clients_->wants_writable()) ms = 0;
    (void)::poll(fds.data(), fds.size(), ms);
  }

  void drain(double now) {
    for (std::size_t reads = 0; reads < kMaxDatagramsPerDrain; ++reads) {
      if (clients_ && clients_->own_room() < kRoomForADatagram) break;  // sent first, then taken in
      if (board_->drain(board_parser_, [&](const mavlink::Frame& f) { on_board_frame(f, now); }, 1) == 0) break;
    }
    if (clients_) {
      clients_->receive_some(kMaxClientDatagramsPerDrain, [&](const net::Datagram& d) {
        clients_parser_.parse_datagram(d.bytes, [&](const mavlink::Frame& f) { router_.route(f, clients_link_, now, d.from); });
      });
    }
    for (auto& e : endpoints_) {
      if (e->link->stats().connects != e->parser_connects) {  // a new TCP connection: a fresh stream
        e->parser_connects = e->link->stats().connects;
        e->parser = std::make_unique<mavlink::FrameParser>(messages_);
      }
      e->link->drain_from(
          *e->parser, [&](const mavlink::Frame& f, const net::SocketAddress& from) { router_.route(f, e->route, now, from); },
          kMaxDatagramsPerDrain);
    }
    say_link_events();
  }

  /// What the --endpoint links said (TCP connected, lost, retrying).
  void say_link_events() {
    for (auto& e : endpoints_)
      for (const auto& ev : e->link->take_events()) observer_.on_event(ev.text, ev.severity);
  }

  void on_board_frame(const mavlink::Frame& f, double now) {
    last_frame_s_ = now;
    track_loss(f);
    if (f.is<msg::Heartbeat>() && f.as<msg::Heartbeat>().autopilot != static_cast<uint8_t>(mavlink::MavAutopilot::Invalid)) {
      last_heartbeat_s_ = now;
      board_sysid_ = f.sysid;
    }
    if (f.is<msg::Timesync>()) {  // our own request's answer: measured, not routed
      const auto t = f.as<msg::Timesync>();
      if (t.tc1 != 0 && t.target_system == kBridgeSystemId && t.target_component == kBridgeComponentId) {
        for (const auto sent : timesync_sent_ns_) {
          if (sent == t.ts1) rtt_ms_ = static_cast<double>(static_cast<int64_t>(monotonic_us()) * 1000 - t.ts1) / 1e6;
        }
        return;
      }
    }
    router_.route(f, board_link_, now);
  }

  /// Per-source loss, for at most kMaxLossSources sources (a board has a handful); frames of
  /// further sources are counted apart and said once.
  void track_loss(const mavlink::Frame& f) {
    const std::string key = source_key(f.sysid, f.compid);
    auto it = sequences_.find(key);
    if (it == sequences_.end()) {
      if (sequences_.size() >= kMaxLossSources) {
        if (untracked_frames_++ == 0)
          observer_.on_event("the board link shows more than " + std::to_string(kMaxLossSources) +
                                 " sources (sysid/compid); loss is tracked for the first ones only (frames of others "
                                 "counted: untracked_frames)",
                             Severity::Warning);
        return;
      }
      it = sequences_.emplace(key, mavlink::SequenceTracker{}).first;
    }
    it->second.observe(f.seq);
  }

  void watch_board(double now) {
    if (last_frame_s_ < 0) return;
    const double silent_s = now - last_frame_s_;
    if (!gone_ && silent_s > kBoardGoneAfter_s && !board_->wait_readable(0)) {  // a board whose datagrams wait is not gone
      gone_ = true;
      gone_since_s_ = last_frame_s_;
      char text[200];
      std::snprintf(text, sizeof text,
                    "board gone: nothing from %s for %.1f s (cable unplugged, PX4 restarted?); every socket stays open, "
                    "traffic resumes when it is back",
                    board_address_->to_string().c_str(), silent_s);
      observer_.on_event(text, Severity::Warning);
    } else if (gone_ && silent_s < kBoardGoneAfter_s) {
      gone_ = false;
      char text[120];
      std::snprintf(text, sizeof text, "board back after %.1f s", now - gone_since_s_);
      observer_.on_event(text, Severity::Info);
    }
  }

  template <class M>
  void send_own(router::LinkId link, const M& message) {
    mavlink::FrameBuffer buf;
    if (const std::size_t n = own_.encode(message, buf)) router_.send(link, {buf.data(), n});
  }

  void tick(double now) {
    // Our HEARTBEAT (an onboard component, not a ground station: PX4's GCS-loss logic must not
    // count the bridge) makes a fresh PX4 instance take this port as its partner.
    send_own(board_link_, mavlink::onboard_heartbeat());
    msg::Timesync ts;
    ts.tc1 = 0;
    ts.ts1 = static_cast<int64_t>(monotonic_us()) * 1000;
    ts.target_system = board_sysid_;
    timesync_sent_ns_.push_back(ts.ts1);
    if (timesync_sent_ns_.size() > kTimesyncRemembered) timesync_sent_ns_.pop_front();
    send_own(board_link_, ts);
    // Each destination's first refused send, said at once; later ones are counted (send_errors).
    for (const auto& text : board_->take_send_errors()) observer_.on_event(text, Severity::Warning);
    for (const auto& e : endpoints_)
      for (const auto& text : e->link->take_send_errors()) observer_.on_event("--endpoint " + e->spec.text + ": " + text, Severity::Warning);
    observer_.on_health(health(now));
  }

  BridgeHealth health(double now) const {
    BridgeHealth h;
    h.uptime_s = now - start_s_;
    h.board_state = last_frame_s_ < 0 ? "waiting" : gone_ ? "gone" : "up";
    if (last_heartbeat_s_ >= 0) h.heartbeat_age_s = now - last_heartbeat_s_;
    h.rtt_ms = rtt_ms_;
    for (const auto& [key, tracker] : sequences_) {
      const auto& s = tracker.stats();
      h.loss[key] = SourceLoss{s.received, s.lost, 100.0 * s.loss_ratio()};
    }
    const auto link_health = [&](router::LinkId id, std::string partner, bool connected, const net::Link* link = nullptr) {
      const auto& c = router_.counters(id);
      LinkHealth l;
      l.name = router_.name(id);
      l.partner = std::move(partner);
      l.connected = connected;
      l.packets_in = c.frames_in;
      l.bytes_in = c.bytes_in;
      l.send_errors = link != nullptr ? link->stats().send_errors : 0;  // one frame a datagram (or write) on these links
      l.packets_out = c.frames_out - std::min(c.frames_out, l.send_errors);
      l.bytes_out = c.bytes_out;
      l.duplicates_in = c.duplicates_in;
      if (link != nullptr) l.kernel_rx_drops = link->stats().kernel_rx_drops;
      return l;
    };
    h.links.push_back(link_health(board_link_, board_address_->to_string(), last_frame_s_ >= 0 && !gone_, board_.get()));
    if (clients_) {
      h.clients = clients_->client_count();
      auto l = link_health(clients_link_, clients_->local_address()->to_string(), h.clients > 0);
      const auto& s = clients_->stats();
      l.deliveries = s.datagrams_out;
      l.dropped = s.dropped_frames;
      l.send_errors = s.send_errors;
      l.send_buffer_full = s.send_buffer_full;
      l.kernel_rx_drops = clients_->kernel_rx_drops();
      h.links.push_back(l);
    }
    uint64_t ignored = board_->stats().ignored_other_address;
    for (const auto& e : endpoints_) {
      const auto peer = e->link->peer();
      h.links.push_back(link_health(e->route, peer ? peer->to_string() : std::string{}, e->link->connected() && peer.has_value(),
                                    e->link.get()));
      ignored += e->link->stats().ignored_other_address;
    }
    h.duplicates = router_.duplicates();
    h.kernel_rx_drops = board_->stats().kernel_rx_drops;
    h.ignored_other_address = ignored;
    h.untracked_frames = untracked_frames_;
    return h;
  }

  const BridgeConfig& config_;
  BridgeObserver& observer_;
  mavlink::MessageSet messages_ = mavlink::MessageSet::compiled();
  router::Router router_;
  mavlink::FrameParser board_parser_;
  mavlink::FrameParser clients_parser_;
  mavlink::FrameEncoder own_;
  std::optional<net::SocketAddress> board_address_;
  std::unique_ptr<net::Link> board_;
  net::UdpEndpoint::BufferSizes board_buffers_;
  std::optional<net::ClientPort> clients_;
  std::vector<std::unique_ptr<Endpoint>> endpoints_;
  router::LinkId board_link_ = 0, clients_link_ = 0;
  std::map<std::string, mavlink::SequenceTracker> sequences_;
  uint64_t untracked_frames_ = 0;
  std::deque<int64_t> timesync_sent_ns_;
  std::optional<double> rtt_ms_;
  uint8_t board_sysid_ = 0;
  double start_s_ = 0, next_tick_s_ = 0;
  double last_frame_s_ = -1, last_heartbeat_s_ = -1, gone_since_s_ = 0;
  bool gone_ = false;
};

}  // namespace

Status run_bridge(const BridgeConfig& config, BridgeObserver& observer, const std::atomic<bool>& stop, bool* opened) {
  Bridge bridge(config, observer);
  if (auto st = bridge.open(); !st) return st;
  if (opened != nullptr) *opened = true;
  observer.on_event(bridge.describe(), Severity::Info);
  return bridge.run(stop);
}

}  // namespace hitl::bridge
