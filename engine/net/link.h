// One MAVLink link, as mavlink-router's Endpoint (src/endpoint.h): the session's flight-stack link,
// a vehicle command's link and the bridge's board and --endpoint links are all a Link, and code
// that reads or sends never asks which kind it holds.
//
//   UdpLink        (udp_link.h)  a UDP socket: a fixed peer (udp:HOST:PORT, the board), or one learnt
//                                from who spoke (udpin:PORT); optionally hears its peer only. The adb
//                                tunnel is behind one: its peer is the tunnel's local end (adb_tunnel.h).
//   TcpClientLink  (tcp_links.h) a TCP connection to a MAVLink server, reconnecting when asked to
//   TcpServerLink  (tcp_links.h) a TCP listener one client connects to (PX4 SITL's simulator link)
//   TcpHubLink     (tcp_hub_link.h) a TCP listener many clients connect to (ground station tools)
//
// Users name them in one grammar (link_spec.h) and open_link() (open_link.h) creates them.
//
// Datagram links carry one or more whole frames per datagram; stream links carry bytes. drain()
// hides the difference: it parses what arrived with the caller's FrameParser either way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "base/common/expected.h"
#include "base/common/severity.h"
#include "base/mavlink/frame_parser.h"
#include "engine/net/socket_address.h"

namespace hitl::net {

struct LinkStats {
  uint64_t datagrams_in = 0;   ///< datagrams (UDP) or reads (TCP) accepted
  uint64_t datagrams_out = 0;  ///< datagrams (UDP) or writes (TCP) that left
  uint64_t bytes_in = 0;
  uint64_t bytes_out = 0;
  uint64_t send_errors = 0;    ///< sends the kernel refused while the link was up (never in datagrams_out);
                               ///< a stream whose peer went away is closed(), not a send error
  int last_send_errno = 0;     ///< the latest refusal's errno, 0 when none
  uint64_t ignored_other_address = 0;  ///< datagrams from another address than the peer (hear_peer_only)
  uint64_t connects = 0;       ///< streams: connections made (a reconnect adds one)
  uint64_t kernel_rx_drops = 0;  ///< datagrams the kernel dropped for a full receive buffer (SO_RXQ_OVFL)
};

/// Something a link says about itself (connected, lost, retrying), for its owner to pass on.
struct LinkEvent {
  std::string text;
  Severity severity = Severity::Info;
};

/// What one read gave: a whole datagram, or a piece of a byte stream.
struct LinkChunk {
  std::span<const uint8_t> bytes;
  SocketAddress from;
  bool whole_datagram = true;
};

class Link {
 public:
  using ChunkHandler = std::function<void(const LinkChunk&)>;
  using SourcedFrameHandler = std::function<void(const mavlink::Frame&, const SocketAddress& from)>;
  static constexpr std::size_t kAll = std::numeric_limits<std::size_t>::max();

  virtual ~Link() = default;
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  /// Reads at most `max_reads` datagrams (or stream pieces) that are waiting, never blocking, and
  /// gives each accepted one to `on_chunk`. Returns how many reads were made (ignored ones too).
  virtual std::size_t read_some(std::size_t max_reads, const ChunkHandler& on_chunk) = 0;
  /// read_some() into a parser: a datagram is parsed as one, stream bytes are fed.
  std::size_t drain(mavlink::FrameParser& parser, const mavlink::FrameParser::FrameHandler& on_frame,
                    std::size_t max_reads = kAll);
  /// drain() that says who sent each frame; a hub parses each client's stream apart (with parsers
  /// of `parser`'s message set).
  virtual std::size_t drain_from(mavlink::FrameParser& parser, const SourcedFrameHandler& on_frame, std::size_t max_reads = kAll);
  /// Waits up to timeout_ms for something to read; false on timeout (or when not connected).
  virtual bool wait_readable(int timeout_ms) const = 0;

  /// Sends now: one datagram, or all bytes on the stream.
  virtual Status send(std::span<const uint8_t> bytes) = 0;
  /// A hub (hub()): sends to every client but `except`, or to those in `only` when it is not empty.
  /// Any other link has one peer: it sends unless that peer is `except` or not in `only`.
  virtual Status send_to_peers(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except,
                               std::span<const SocketAddress> only);
  /// Adds a frame to what flush() sends as one datagram (or one write); check has_room_for() first.
  virtual void queue(std::span<const uint8_t> frame) = 0;
  virtual bool has_room_for(std::size_t bytes) const = 0;
  std::size_t queued_bytes() const { return tx_.size(); }
  /// Sends what queue() collected; Ok when there was nothing.
  virtual Status flush() = 0;

  /// Blocks up to timeout_ms until the link can carry traffic (a server: a client connected).
  virtual bool wait_connected(int /*timeout_ms*/) { return connected(); }
  /// Makes the link up again when it is down and it reconnects by itself (a TCP client); cheap.
  virtual void maintain(double /*now_s*/) {}

  /// Many peers at once (a TCP listener ground station tools connect to): a router's hub link.
  virtual bool hub() const { return false; }
  /// Can carry traffic now: a UDP socket always, a stream while connected.
  virtual bool connected() const = 0;
  /// A stream that was up and went away without coming back by itself (PX4 SITL never reconnects).
  virtual bool closed() const { return false; }
  /// Who the link talks to: the fixed or learnt UDP peer, the server, the connected client.
  virtual std::optional<SocketAddress> peer() const = 0;
  virtual std::optional<SocketAddress> local_address() const = 0;
  /// For poll(): -1 while there is nothing to wait on.
  virtual int fd() const = 0;

  /// The first refused send to each destination, once, in words (errno and the likely fix).
  virtual std::vector<std::string> take_send_errors() { return {}; }
  /// What the link said since the last call.
  std::vector<LinkEvent> take_events() { return std::exchange(events_, {}); }
  virtual const LinkStats& stats() const { return stats_; }
  const std::string& name() const { return name_; }

 protected:
  explicit Link(std::string name) : name_(std::move(name)) {}
  void say(std::string text, Severity severity) { events_.push_back({std::move(text), severity}); }

  std::string name_;
  LinkStats stats_;
  std::vector<uint8_t> tx_;  ///< what queue() collected
  std::vector<LinkEvent> events_;
};

}  // namespace hitl::net
