#include "engine/bridge/bridge.h"

#include <poll.h>

#include <algorithm>
#include <cmath>
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
/// The board is read only while every ?lossless endpoint's queue has room for this many more
/// frames (a datagram's worth): what is taken in reaches it, and a board faster than it waits in
/// the kernel's receive buffer (sized to --queue-ms), whose overflow is counted (kernel_rx_drops).
constexpr std::size_t kRoomForADatagram = 128;
/// The client port sized for a 100-client fan-out of a flat-out board stream; its queue is fresh
/// (max_queue_s from --queue-ms). A pump sends at most 1,024 datagrams (~3 ms), so the board is
/// read often enough that its socket holds no old backlog.
constexpr net::ClientPortLimits kClientLimits{.max_clients = 128,
                                              .max_datagrams_out = 1024,
                                              .max_queued_frames = 2048,
                                              .send_buffer_bytes = 4 << 20,
                                              .receive_buffer_bytes = 1 << 20,
                                              .max_queue_s = 0,
                                              .min_queued_frames = kMinClientQueueFrames};
constexpr double kDefaultDatagramTruesize_bytes = 1024;  ///< the kernel's cost of one small datagram, until measured

std::string format_ms(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%g ms", ms);
  return text;
}

std::string source_key(uint8_t sysid, uint8_t compid) { return std::to_string(sysid) + "/" + std::to_string(compid); }

/// One --endpoint: its link, its parser and its place in the router.
struct Endpoint {
  net::LinkSpec spec;
  std::unique_ptr<net::Link> link;
  net::UdpLink* udp = nullptr;  ///< the same link when it is UDP (udp:, udpin:)
  /// ?lossless: frames that found the send buffer full, sent in order once it is writable.
  std::deque<std::vector<uint8_t>> waiting;
  uint64_t dropped = 0, send_buffer_full = 0;
  std::map<uint32_t, uint64_t> dropped_by_msgid;
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
    // udp:BOARD:PORT from the fixed --local-port, through the one factory; typed, for the socket's
    // buffer and drop figures (size_board_buffer, poll_kernel_drops).
    net::LinkSpec board;
    board.kind = net::LinkSpec::Kind::Udp;
    board.host = config_.board_ip;  // resolved above: the same address, with the -i error
    board.port = config_.board_port;
    board.text = board.to_string();
    net::LinkSettings settings;
    settings.name = "the board link's local port (--local-port)";
    settings.local_port = config_.local_port;
    settings.hear_peer_only = true;  // the board answers from its own port; anyone else is not the board
    settings.receive_buffer_bytes = board_buffer_asked_ = kBoardReceiveMin_bytes;  // grows with the stream (size_board_buffer)
    auto ep = net::open_udp_link(board, settings);
    if (!ep) return ep.error().suffixed(" (a hitl sim, another hitl bridge or a direct command owns it?)");
    board_buffers_ = ep.value()->buffer_sizes();
    board_udp_ = ep.value().get();
    board_ = std::move(ep.value());
    board_link_ = router_.add_link("board", [this](std::span<const uint8_t> bytes, const auto&) { (void)board_->send(bytes); });

    if (config_.clients_port != 0) {
      net::ClientPortLimits limits = kClientLimits;
      limits.max_queue_s = config_.queue_ms / 1000.0;
      auto cp = net::ClientPort::open(config_.clients_bind, config_.clients_port, {}, limits);
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
      e->udp = dynamic_cast<net::UdpLink*>(e->link.get());
      Endpoint* raw = e.get();
      e->route = router_.add_link(
          spec.text,
          [this, raw](std::span<const uint8_t> bytes, const router::Delivery& to) { send_to_endpoint(*raw, bytes, to); },
          /*hub=*/raw->link->hub());
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
    std::string out = "socket buffers granted: board receive " + granted(board_buffer_asked_, board_buffers_.receive_bytes, "net.core.rmem_max") +
                      " (then sized to " + format_ms(kBoardBuffer_ms) + " of the board's stream)";
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
    last_sized_s_ = start_s_;
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
      send_waiting();
      drain(monotonic_s());
      if (clients_) clients_->pump();
      send_waiting();
      watch_board(monotonic_s());
    }
    return Ok{};
  }

 private:
  void wait_readable(double timeout_ms) {
    std::vector<pollfd> fds;
    // A board faster than a ?lossless endpoint waits in its socket while that endpoint's queue is full.
    if (lossless_room()) fds.push_back({board_->fd(), POLLIN, 0});
    if (clients_) fds.push_back({clients_->fd(), static_cast<short>(POLLIN | (clients_->wants_writable() ? POLLOUT : 0)), 0});
    for (const auto& e : endpoints_)
      if (e->link->fd() >= 0) fds.push_back({e->link->fd(), static_cast<short>(POLLIN | (e->waiting.empty() ? 0 : POLLOUT)), 0});
    int ms = std::max(0, static_cast<int>(timeout_ms));
    // The client port's send bound left some for later: go on at once (unless its buffer is full).
    if (clients_ && clients_->queued_frames() > 0 && !clients_->wants_writable()) ms = 0;
    (void)::poll(fds.data(), fds.size(), ms);
  }

  /// Room in every ?lossless endpoint's queue for another datagram's frames (true without any).
  bool lossless_room() const {
    return std::all_of(endpoints_.begin(), endpoints_.end(),
                       [](const auto& e) { return e->waiting.size() + kRoomForADatagram <= kMaxLosslessQueueFrames; });
  }

  /// Board datagrams read per loop turn: four times what a turn sends to the clients (the newest
  /// are taken in and the oldest dropped, without reading a hundred frames for each one a
  /// 100-client fan-out can send), at least 32, at most kMaxDatagramsPerDrain.
  std::size_t board_reads_per_turn() const {
    if (!clients_ || clients_->client_count() == 0) return kMaxDatagramsPerDrain;
    const std::size_t per_turn = 4 * kClientLimits.max_datagrams_out / clients_->client_count();
    return std::clamp<std::size_t>(per_turn, 32, kMaxDatagramsPerDrain);
  }

  void drain(double now) {
    // The board is read as fast as it sends (what is too old is dropped in the clients' queue,
    // oldest first, and counted by message); its socket's backlog is what the loop left unread.
    const std::size_t waiting_bytes = board_udp_->receive_queue_bytes();
    const std::size_t max_reads = board_reads_per_turn();
    std::size_t reads = 0;
    for (; reads < max_reads; ++reads) {
      if (!lossless_room()) break;  // sent first, then taken in
      if (board_->drain(board_parser_, [&](const mavlink::Frame& f) { on_board_frame(f, now); }, 1) == 0) break;
    }
    board_reads_ += reads;
    // Emptied: what the socket held per datagram (the kernel's cost, to size its buffer in time).
    if (reads > 0 && reads < max_reads && waiting_bytes > 0) {
      const double per = static_cast<double>(waiting_bytes) / static_cast<double>(reads);
      datagram_truesize_ = datagram_truesize_ <= 0 ? per : 0.9 * datagram_truesize_ + 0.1 * per;
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

  /// One frame to an --endpoint. udpin: nobody to answer until someone spoke; tcp: nothing while
  /// disconnected. A full send buffer: a ?lossless endpoint keeps the frame (and the board waits
  /// in its socket once the queue is full); a fresh one drops it, counted by message.
  void send_to_endpoint(Endpoint& e, std::span<const uint8_t> bytes, const router::Delivery& to) {
    // udpin: nobody to answer until someone spoke; tcp, tcpin: nothing while disconnected
    if (!e.link->connected() || !e.link->peer()) return;
    if (e.udp == nullptr) {  // a stream: the link queues what the reader has not taken (tcpin: each client's)
      (void)e.link->send_to_peers(bytes, to.except, to.only);
      return;
    }
    if (e.spec.lossless && !e.waiting.empty()) {
      if (e.waiting.size() < kMaxLosslessQueueFrames) e.waiting.emplace_back(bytes.begin(), bytes.end());
      else count_drop(e, bytes);  // only frames from clients and endpoints, which are not held back, can get here
      return;
    }
    if (e.udp->try_send(bytes) != net::SendOutcome::WouldBlock) return;  // a refusal is counted in send_errors
    ++e.send_buffer_full;
    if (e.spec.lossless) e.waiting.emplace_back(bytes.begin(), bytes.end());
    else count_drop(e, bytes);
  }

  void count_drop(Endpoint& e, std::span<const uint8_t> bytes) {
    ++e.dropped;
    uint32_t id = bytes.size() >= 10 && bytes[0] == 0xFD ? (uint32_t{bytes[7]} | uint32_t{bytes[8]} << 8 | uint32_t{bytes[9]} << 16)
                  : bytes.size() >= 6 && bytes[0] == 0xFE ? bytes[5] : net::ClientPort::kOtherIds;
    if (!e.dropped_by_msgid.contains(id) && e.dropped_by_msgid.size() >= net::ClientPort::kMaxDropIds) id = net::ClientPort::kOtherIds;
    ++e.dropped_by_msgid[id];
  }

  /// ?lossless endpoints: what waited for the send buffer, in order, until it is full again.
  void send_waiting() {
    for (auto& e : endpoints_) {
      while (!e->waiting.empty() && e->udp != nullptr) {
        const auto sent = e->udp->try_send(e->waiting.front());
        if (sent == net::SendOutcome::WouldBlock) {
          ++e->send_buffer_full;
          break;
        }
        e->waiting.pop_front();
      }
    }
  }

  /// The board socket's receive buffer holds kBoardBuffer_ms of the board's stream as it arrived
  /// in the last period (read or dropped by the kernel) (the kernel doubles what it is asked for): under overload the kernel drops the
  /// rest (counted) instead of keeping seconds of backlog; at a board's usual rates the minimum holds.
  void size_board_buffer(double now) {
    const double period_s = now - last_sized_s_;
    if (period_s <= 0) return;
    // The board's stream: what was read and what the kernel dropped (sized by what was read
    // alone, a buffer that overflows would shrink itself further).
    const uint64_t arrived = board_reads_ + board_->stats().kernel_rx_drops;
    const double rate_hz = static_cast<double>(arrived - arrived_at_last_size_) / period_s;
    last_sized_s_ = now;
    arrived_at_last_size_ = arrived;
    const double truesize = datagram_truesize_ > 0 ? datagram_truesize_ : kDefaultDatagramTruesize_bytes;
    const double want = rate_hz * truesize * kBoardBuffer_ms / 1000.0 / 2.0;
    const int asked = static_cast<int>(std::clamp(want, static_cast<double>(kBoardReceiveMin_bytes), static_cast<double>(kBoardReceiveMax_bytes)));
    if (std::abs(asked - board_buffer_asked_) * 5 < board_buffer_asked_) return;  // within 20 %: leave it
    board_buffer_asked_ = asked;
    board_udp_->set_receive_buffer(asked);
    board_buffers_ = board_udp_->buffer_sizes();
  }

  std::string message_name(uint32_t id) const {
    if (id == net::ClientPort::kOtherIds) return "other";
    const auto* d = messages_.find(id);
    return d != nullptr ? d->name : std::to_string(id);
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
    // The kernel's drops read now, not only with the next datagram: a flood that ends the stream
    // leaves nothing after it to carry the count.
    board_udp_->poll_kernel_drops();
    if (clients_) clients_->poll_kernel_drops();
    for (auto& e : endpoints_)
      if (e->udp != nullptr) e->udp->poll_kernel_drops();
    size_board_buffer(now);
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
      l.dropped = s.dropped_deliveries;
      for (const auto& [id, n] : s.dropped_by_msgid) l.dropped_by_message[message_name(id)] += n;
      l.send_errors = s.send_errors;
      l.send_buffer_full = s.send_buffer_full;
      l.kernel_rx_drops = clients_->kernel_rx_drops();
      h.links.push_back(l);
    }
    uint64_t ignored = board_->stats().ignored_other_address;
    for (const auto& e : endpoints_) {
      const auto peer = e->link->peer();
      auto l = link_health(e->route, peer ? peer->to_string() : std::string{}, e->link->connected() && peer.has_value(), e->link.get());
      l.lossless = e->spec.lossless;
      l.dropped = e->dropped;
      l.packets_out -= std::min<uint64_t>(l.packets_out, e->dropped + e->waiting.size());  // routed there but not (yet) sent
      l.send_buffer_full = e->send_buffer_full;
      for (const auto& [id, n] : e->dropped_by_msgid) l.dropped_by_message[message_name(id)] += n;
      h.links.push_back(std::move(l));
      ignored += e->link->stats().ignored_other_address;
    }
    h.duplicates = router_.duplicates();
    h.kernel_rx_drops = board_->stats().kernel_rx_drops;
    h.board_receive_buffer_bytes = board_buffers_.receive_bytes;
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
  net::UdpLink* board_udp_ = nullptr;  ///< the same link: its socket's buffer and drop count
  net::UdpEndpoint::BufferSizes board_buffers_;
  int board_buffer_asked_ = 0;
  uint64_t board_reads_ = 0, arrived_at_last_size_ = 0;
  double last_sized_s_ = 0, datagram_truesize_ = 0;
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
