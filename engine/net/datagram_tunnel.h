// The host side of a UDP-over-TCP tunnel to hitl-adb-relay (target/adb-relay, docs/adb.md): per
// channel (HIL, VIO, GCS) a local UDP socket on 127.0.0.1 that stands for the board's port, and one
// framed TCP stream that carries them all. Local code sends to local_endpoint(channel) as if it were
// the board; replies come back from that same address to whoever sent last on it. A pump thread
// moves datagrams both ways, pings the relay every second (round-trip time, and a dead link is
// noticed within link_timeout), and reconnects through the Connector when the stream is lost,
// while the local sockets stay open.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "base/common/expected.h"
#include "base/contract/framed_stream.h"
#include "base/contract/tunnel_protocol.h"
#include "engine/net/socket_address.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::net {

/// Connecting to a relay: TCP connect, hellos both ways, versions compared.
struct RelayConnection {
  std::unique_ptr<adb::FramedStream> stream;  ///< set on success
  std::string error;                          ///< why not, in words
  /// Nothing answered as a relay: connection refused, or closed before a byte of hello (what adb
  /// does when nothing listens on the board's port). A relay that answered wrongly is not absent.
  bool relay_absent = false;
};
RelayConnection connect_to_relay(const SocketAddress& address, int timeout_ms);

struct TunnelChannelStats {
  uint64_t to_board = 0;           ///< datagrams from local clients into the stream
  uint64_t from_board = 0;         ///< datagrams from the stream to a local client
  uint64_t bytes_to_board = 0;
  uint64_t bytes_from_board = 0;
  uint64_t dropped_no_link = 0;    ///< local datagrams while the relay was not connected
  uint64_t dropped_backlog = 0;    ///< local datagrams the stream could not take
  uint64_t dropped_too_large = 0;  ///< local datagrams over the tunnel's limit
  uint64_t dropped_no_client = 0;  ///< board datagrams before any local client had sent on the channel
};

struct TunnelStats {
  bool connected = false;
  uint64_t connects = 0;        ///< successful connections (the first one included)
  uint64_t link_losses = 0;
  std::optional<double> rtt_ms;      ///< the last ping's round trip through the stream and the relay
  double rtt_max_ms = 0;
  std::string last_error;            ///< why the link was last lost or could not be made
  TunnelChannelStats channels[adb::kChannelCount];
};

class DatagramTunnel {
 public:
  /// Makes (or remakes) the stream; called at open() and, from the pump thread, after a loss.
  using Connector = std::function<Expected<std::unique_ptr<adb::FramedStream>>()>;
  using EventSink = std::function<void(const std::string& line)>;

  struct Config {
    std::string local_address = "127.0.0.1";  ///< where the local UDP sockets bind (ephemeral ports)
    int ping_period_ms = 1000;
    int link_timeout_ms = 3000;      ///< nothing from the relay this long: the link is lost
    int reconnect_period_ms = 1000;  ///< between attempts while the link is down
    EventSink on_event;              ///< link lost / restored, in words (from the pump thread)
  };

  /// Opens the local sockets, connects once (its error is returned) and starts the pump.
  static Expected<std::unique_ptr<DatagramTunnel>> open(const Config& config, Connector connector);
  ~DatagramTunnel();
  DatagramTunnel(const DatagramTunnel&) = delete;
  DatagramTunnel& operator=(const DatagramTunnel&) = delete;

  /// Where local code sends to reach the board's port for `channel`: "127.0.0.1:40123".
  const SocketAddress& local_endpoint(adb::Channel channel) const;
  TunnelStats stats() const;

 private:
  class StreamEvents;
  DatagramTunnel(const Config& config, Connector connector);
  void pump();
  void lose_link(const std::string& why);
  void read_local(adb::Channel channel);
  void emit(const std::string& line) const;

  Config config_;
  Connector connector_;
  std::optional<UdpEndpoint> local_[adb::kChannelCount];
  SocketAddress local_address_[adb::kChannelCount];
  std::unique_ptr<adb::FramedStream> stream_;
  int wake_fd_ = -1;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  int64_t last_rx_ms_ = 0;
  uint64_t last_bytes_in_ = 0;
  mutable std::mutex stats_mutex_;
  TunnelStats stats_;
};

}  // namespace hitl::net
