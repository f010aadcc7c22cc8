// An IPv4/IPv6 UDP or TCP address, and parsing of the "HOST:PORT" forms users type.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "base/common/expected.h"

namespace hitl::net {

class SocketAddress {
 public:
  SocketAddress() = default;
  SocketAddress(const sockaddr* addr, socklen_t len);

  /// Resolves a numeric or named host ("127.0.0.1", "localhost", "::1") with a port.
  static Expected<SocketAddress> resolve(const std::string& host, uint16_t port);
  /// "HOST:PORT" or "[V6]:PORT"; `what` names the input in errors ("--connect").
  static Expected<SocketAddress> parse(std::string_view host_port, std::string_view what);

  const sockaddr* get() const { return reinterpret_cast<const sockaddr*>(&storage_); }
  socklen_t length() const { return length_; }
  int family() const { return storage_.ss_family; }
  uint16_t port() const;
  std::string host() const;
  bool is_loopback() const;
  /// "127.0.0.1:14560" / "[::1]:14560".
  std::string to_string() const;

  bool operator==(const SocketAddress& other) const;
  bool operator!=(const SocketAddress& other) const { return !(*this == other); }
  bool operator<(const SocketAddress& other) const { return to_string() < other.to_string(); }

 private:
  sockaddr_storage storage_{};
  socklen_t length_ = 0;
};

/// The board's address as -i gives it: resolve(), with errors that name the option.
Expected<SocketAddress> resolve_board_address(const std::string& host, uint16_t port);

/// A port number from text, 1..65535 (0 too when `allow_zero`); errors name `what`.
Expected<uint16_t> parse_port(std::string_view text, std::string_view what, bool allow_zero = false);

}  // namespace hitl::net
