// The port local MAVLink clients talk to while a session or bridge owns the board link
// (127.0.0.1:14600 by default): it learns each client from the datagrams it sends, forgets one
// after a silence, and sends board traffic to every client it knows plus any fixed peers (a GCS).
// Frames are never echoed to the client that sent them.
//
// Bounded, so that the loop that owns it (the session's 4 ms step) never does work that grows with
// the number of clients or with what they send:
// - at most `max_clients` clients at a time; datagrams from further senders are read and dropped
//   (counted in `refused_datagrams`) until one of the known clients goes silent;
// - receive_some() reads at most the number of datagrams it is given;
// - broadcast() only queues the frame; pump() sends at most `max_datagrams_out` datagrams per call,
//   frames from the board and the owner's own first, then client-to-client ones; each of the two
//   queues holds at most `max_queued_frames` frames, and a frame that finds its queue full is
//   dropped and counted (`dropped_frames`);
// - fresh queues (limits.max_queue_s > 0, the bridge): the board's queue holds at most that much
//   sending time, measured (seconds per datagram sent, times the clients), so under overload a
//   client gets frames at most ~max_queue_s old; a frame that finds it full drops the OLDEST frame
//   (the newest ATTITUDE is what a flight link wants), counted per client it did not reach
//   (`dropped_deliveries`) and per MAVLink message id (`dropped_by_msgid`);
// - a send that finds the socket's buffer full (EAGAIN, ENOBUFS) is not lost: pump() stops there
//   and carries on with the same client when the socket is writable (wants_writable(): poll POLLOUT).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::net {

struct ClientPortLimits {
  std::size_t max_clients = 64;
  std::size_t max_datagrams_out = 256;  ///< per pump()
  std::size_t max_queued_frames = 512;  ///< per queue (board/own, client-to-client)
  int send_buffer_bytes = 0;            ///< SO_SNDBUF asked for (0: the kernel's default)
  int receive_buffer_bytes = 1 << 20;   ///< SO_RCVBUF asked for
  /// > 0: the board's queue is sized in sending time: at most this many seconds of sends (the
  /// measured time per datagram times the clients), at least min_queued_frames and what one pump()
  /// sends to every client, at most
  /// max_queued_frames; a full queue drops its oldest frame. 0: max_queued_frames, a full queue
  /// refuses the newest (the session's clients).
  double max_queue_s = 0;
  std::size_t min_queued_frames = 16;
};

struct ClientPortStats {
  uint64_t datagrams_in = 0;
  uint64_t datagrams_out = 0;
  uint64_t send_errors = 0;        ///< datagrams the kernel refused (not a full buffer: that waits)
  uint64_t refused_datagrams = 0;  ///< from senders beyond max_clients: dropped
  uint64_t dropped_frames = 0;     ///< frames that found their send queue full
  uint64_t send_buffer_full = 0;   ///< times a send found the socket's buffer full (EAGAIN/ENOBUFS): kept, sent when writable
  uint64_t dropped_deliveries = 0; ///< datagrams never sent because their frame was dropped: one per frame and client it had not reached
  /// dropped_deliveries by MAVLink message id (at most kMaxDropIds ids; the rest under kOtherIds)
  std::map<uint32_t, uint64_t> dropped_by_msgid;
};

class ClientPort {
 public:
  static constexpr std::chrono::seconds kClientTimeout{10};
  static constexpr std::size_t kMaxFrameBytes = 280;  ///< one MAVLink 2 frame, signed
  static constexpr std::size_t kMaxDropIds = 64;        ///< message ids counted apart in dropped_by_msgid
  static constexpr uint32_t kOtherIds = 0xFFFFFFFF;     ///< dropped_by_msgid's key for the rest
  static constexpr double kAssumedSendTime_s = 5e-6;    ///< per datagram, until pump() has measured it

  /// Binds bind_address:port (port 0: no listening socket, only the fixed peers).
  static Expected<ClientPort> open(const std::string& bind_address, uint16_t port,
                                   const std::vector<SocketAddress>& fixed_peers,
                                   const ClientPortLimits& limits = {});

  /// Reads at most `max_datagrams` waiting datagrams; calls `on_datagram` for each from a client
  /// (learning it). Returns how many were read, refused ones included.
  std::size_t receive_some(std::size_t max_datagrams, const std::function<void(const Datagram&)>& on_datagram);
  /// Queues one frame for every live client and fixed peer except `except` (a client's own frame
  /// going to the others when set), or, when `only` is not empty, for those of them in `only` (a
  /// targeted frame: the clients that showed its target); pump() sends it.
  void broadcast(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except = std::nullopt,
                 const std::vector<SocketAddress>& only = {});
  /// Forgets silent clients and sends at most limits.max_datagrams_out queued datagrams.
  void pump();

  std::size_t client_count() const { return clients_.size(); }
  std::size_t queued_frames() const { return own_.frames.size() + forwarded_.frames.size(); }
  /// Room left in the queue of frames from the board and the owner.
  std::size_t own_room() const { return limits_.max_queued_frames - std::min(limits_.max_queued_frames, own_.frames.size()); }
  /// How many frames each queue holds now (max_queue_s: from the measured sending time).
  std::size_t queue_limit() const;
  /// The measured sending time per datagram (seconds), 0 before it is known.
  double send_time_per_datagram_s() const { return send_s_per_datagram_; }
  /// The last pump() stopped on a full send buffer: wait for POLLOUT before pumping again.
  bool wants_writable() const { return blocked_ && queued_frames() > 0; }
  UdpEndpoint::BufferSizes buffer_sizes() const { return endpoint_ ? endpoint_->buffer_sizes() : UdpEndpoint::BufferSizes{}; }
  uint64_t kernel_rx_drops() const { return endpoint_ ? endpoint_->stats().kernel_rx_drops : 0; }
  /// UdpEndpoint::poll_kernel_drops(): the drop count now, not only with the next datagram.
  void poll_kernel_drops() {
    if (endpoint_) endpoint_->poll_kernel_drops();
  }
  std::vector<SocketAddress> clients() const;
  const ClientPortStats& stats() const { return stats_; }
  const ClientPortLimits& limits() const { return limits_; }
  int fd() const { return endpoint_ ? endpoint_->fd() : -1; }
  std::optional<SocketAddress> local_address() const;

 private:
  struct Client {
    SocketAddress address;
    std::chrono::steady_clock::time_point last_heard;
    bool fixed;
  };
  struct Frame {
    std::array<uint8_t, kMaxFrameBytes> bytes;
    std::size_t size = 0;
    std::optional<SocketAddress> except;
    std::vector<SocketAddress> only;  ///< empty: every client
  };
  /// Frames waiting, and how many clients the front one has been offered to.
  struct Queue {
    std::deque<Frame> frames;
    std::size_t next_client = 0;
  };
  void forget_silent_clients();
  /// Sends from `queue` until it is empty, `budget` runs out or the send buffer is full.
  void send_from(Queue& queue, std::size_t& budget);
  /// Drops the queue's oldest frame, counting the clients it had not reached yet.
  void drop_oldest(Queue& queue);

  std::optional<UdpEndpoint> endpoint_;
  ClientPortLimits limits_;
  std::vector<Client> clients_;
  Queue own_;        ///< from the board and the owner itself
  Queue forwarded_;  ///< from one client to the others
  ClientPortStats stats_;
  bool blocked_ = false;
  double send_s_per_datagram_ = 0;  ///< measured in pump(), smoothed
};

}  // namespace hitl::net
