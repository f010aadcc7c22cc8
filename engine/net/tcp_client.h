// A TCP connection to a MAVLink server (mavlink-router's TCP port, MAVProxy's, a PX4 instance
// started with -t): a byte stream, so frames are parsed with FrameParser::feed.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/socket_address.h"

namespace hitl::net {

class TcpClient {
 public:
  /// Connects within timeout_ms; an Error naming the address when it cannot.
  static Expected<TcpClient> connect(const SocketAddress& to, int timeout_ms, const std::string& name);
  TcpClient(TcpClient&& other) noexcept;
  TcpClient& operator=(TcpClient&& other) noexcept;
  TcpClient(const TcpClient&) = delete;
  TcpClient& operator=(const TcpClient&) = delete;
  ~TcpClient();

  Status send(std::span<const uint8_t> bytes);
  bool wait_readable(int timeout_ms) const;
  /// What is waiting (empty when nothing); an Error when the server closed the connection.
  Expected<std::span<const uint8_t>> receive();
  const SocketAddress& peer() const { return peer_; }
  int fd() const { return fd_; }

 private:
  TcpClient(int fd, SocketAddress peer, std::string name) : fd_(fd), peer_(peer), name_(std::move(name)), buffer_(65536) {}
  int fd_ = -1;
  SocketAddress peer_;
  std::string name_;
  std::vector<uint8_t> buffer_;
};

}  // namespace hitl::net
