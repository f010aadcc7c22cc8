// hitl-adb-relay's work: listen on a TCP port on the board (reached through `adb forward`),
// accept the host's framed stream (framed_stream.h) and turn each frame back into a UDP datagram
// to the board's port for its channel; the replies go back over the stream, tagged the same way.
//
// One host at a time: a new connection replaces the current one (the newest host wins, so a host
// that vanished without closing, a killed adb server say, never locks the next one out).
// The UDP sockets live as long as the relay, not the connection, so the board's MAVLink
// instances keep hearing the same source port across host reconnects.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "base/contract/framed_stream.h"
#include "base/contract/tunnel_protocol.h"

namespace hitl::adb {

struct RelayConfig {
  std::string bind_address = "127.0.0.1";  ///< --bind: adbd connects from the board itself
  uint16_t tcp_port = kRelayTcpPort;       ///< --port (0: any free port, tests)
  uint16_t hil_port = kBoardHilPort;       ///< --hil-port: the HIL channel's target on 127.0.0.1
  uint16_t vio_port = kBoardVioPort;       ///< --vio-port
  uint16_t gcs_port = kBoardGcsPort;       ///< --gcs-port
  uint16_t hil_source_port = kRelayHilSourcePort;  ///< --hil-source-port (0: any)
  uint16_t gcs_source_port = kRelayGcsSourcePort;  ///< --gcs-source-port (0: any)
  int hello_timeout_ms = 5000;             ///< a host that sends no hello this long is dropped
  bool verbose = false;                    ///< --verbose: counters every 10 s, each failed send, each oversize datagram
};

/// Per channel, board side.
struct RelayChannelStats {
  uint64_t to_board = 0;          ///< datagrams from the host sent to the board's port
  uint64_t from_board = 0;        ///< datagrams from the board's port sent to the host
  uint64_t dropped_no_host = 0;   ///< board datagrams while no host was connected
  uint64_t dropped_backlog = 0;   ///< board datagrams the stream could not take (host not reading)
  uint64_t dropped_too_large = 0; ///< board datagrams over kMaxDatagram_bytes
  uint64_t send_errors = 0;       ///< sends to the board's port that failed (nothing listening)
};

struct RelayStats {
  uint64_t connections = 0;        ///< hosts accepted (hello exchanged)
  uint64_t replaced = 0;           ///< connections a newer one replaced
  uint64_t malformed = 0;          ///< connections dropped for a malformed stream or hello
  uint64_t version_mismatches = 0;
  bool host_connected = false;
  RelayChannelStats channels[kChannelCount];
};

class Relay {
 public:
  using Log = std::function<void(const std::string& line)>;

  /// Binds the TCP listener and the per-channel UDP sockets; nullptr and `error` (naming the
  /// address and the problem) when one cannot be opened.
  static std::unique_ptr<Relay> open(const RelayConfig& config, Log log, std::string* error);
  ~Relay();
  Relay(const Relay&) = delete;
  Relay& operator=(const Relay&) = delete;

  /// Serves hosts until `stop` turns true (checked at least every 100 ms and after any signal).
  void run(const std::atomic<bool>& stop);

  /// "127.0.0.1:14590"
  std::string listen_address() const;
  uint16_t tcp_port() const { return tcp_port_; }
  RelayStats stats() const;

 private:
  class HostEvents;
  Relay(const RelayConfig& config, Log log);

  void accept_host();
  void drop_host(const std::string& why, bool malformed);
  void read_host();
  void read_board(adb::Channel channel);
  void send_to_board(adb::Channel channel, const uint8_t* payload, std::size_t size);
  void log_counters();

  RelayConfig config_;
  Log log_;
  int listen_fd_ = -1;
  uint16_t tcp_port_ = 0;
  int udp_fd_[kChannelCount] = {-1, -1, -1, -1};
  uint16_t target_port_[kChannelCount] = {0, 0, 0, 0};
  bool refused_logged_[kChannelCount] = {false, false, false, false};
  std::unique_ptr<FramedStream> host_;
  std::string host_name_;
  int64_t host_hello_deadline_ms_ = 0;
  std::vector<uint8_t> udp_buffer_;
  mutable std::mutex stats_mutex_;
  RelayStats stats_;
};

}  // namespace hitl::adb
