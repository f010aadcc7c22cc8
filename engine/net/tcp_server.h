// A TCP listener that serves one client at a time (PX4 SITL's simulator link: the simulator
// listens on 4560, PX4 connects once and never reconnects).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/socket_address.h"

namespace hitl::net {

class TcpServer {
 public:
  static Expected<TcpServer> listen(const std::string& bind_address, uint16_t port, const std::string& name);
  TcpServer(TcpServer&& other) noexcept;
  TcpServer& operator=(TcpServer&& other) noexcept;
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;
  ~TcpServer();

  /// Waits up to timeout_ms for a client; true once one is connected (TCP_NODELAY set).
  bool accept_client(int timeout_ms);
  bool connected() const { return client_fd_ >= 0; }
  const std::optional<SocketAddress>& client() const { return client_addr_; }
  /// Reads what is waiting without blocking. An Error when the client has gone.
  Expected<std::span<const uint8_t>> receive();
  /// Sends all bytes (blocking); an Error when the client has gone.
  Status send(std::span<const uint8_t> bytes);
  bool wait_readable(int timeout_ms) const;
  int client_fd() const { return client_fd_; }
  const SocketAddress& local_address() const { return local_; }

 private:
  TcpServer(int fd, SocketAddress local, std::string name);
  void drop_client();

  int listen_fd_ = -1;
  int client_fd_ = -1;
  SocketAddress local_;
  std::optional<SocketAddress> client_addr_;
  std::string name_;
  std::vector<uint8_t> buffer_;
};

}  // namespace hitl::net
