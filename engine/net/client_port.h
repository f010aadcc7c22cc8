// The port local MAVLink clients talk to while a session or bridge owns the board link
// (127.0.0.1:14600 by default): it learns each client from the datagrams it sends, forgets one
// after a silence, and sends board traffic to every client it knows plus any fixed peers (a GCS).
// Frames are never echoed to the client that sent them.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/common/expected.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::net {

struct ClientPortStats {
  uint64_t datagrams_in = 0;
  uint64_t datagrams_out = 0;
  uint64_t send_errors = 0;
};

class ClientPort {
 public:
  static constexpr std::chrono::seconds kClientTimeout{10};

  /// Binds bind_address:port (port 0: no listening socket, only the fixed peers).
  static Expected<ClientPort> open(const std::string& bind_address, uint16_t port,
                                   const std::vector<SocketAddress>& fixed_peers);

  /// The next datagram from a client (learning it), or nullopt when none waits.
  std::optional<Datagram> receive();
  /// Sends to every live client and fixed peer except `except`.
  void broadcast(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except = std::nullopt);

  std::size_t client_count() const { return clients_.size(); }
  std::vector<SocketAddress> clients() const;
  const ClientPortStats& stats() const { return stats_; }
  int fd() const { return endpoint_ ? endpoint_->fd() : -1; }
  std::optional<SocketAddress> local_address() const;

 private:
  struct Client {
    SocketAddress address;
    std::chrono::steady_clock::time_point last_heard;
    bool fixed;
  };
  std::optional<UdpEndpoint> endpoint_;
  std::vector<Client> clients_;
  ClientPortStats stats_;
};

}  // namespace hitl::net
