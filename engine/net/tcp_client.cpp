#include "engine/net/tcp_client.h"

#include <fcntl.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hitl::net {

Expected<TcpClient> TcpClient::connect(const SocketAddress& to, int timeout_ms, const std::string& name) {
  const int fd = ::socket(to.family(), SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return Error::unavailable(name + ": cannot create a TCP socket: " + std::strerror(errno));
  if (::connect(fd, to.get(), to.length()) != 0 && errno != EINPROGRESS) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    return Error::failed(name + ": cannot connect to TCP " + to.to_string() + ": " + why);
  }
  pollfd p{fd, POLLOUT, 0};
  int err = 0;
  socklen_t len = sizeof err;
  if (::poll(&p, 1, timeout_ms) <= 0 || ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0 || err != 0) {
    ::close(fd);
    return Error::failed(name + ": cannot connect to TCP " + to.to_string() + ": " + (err ? std::strerror(err) : "timed out"));
  }
  const int on = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  return TcpClient(fd, to, name);
}

TcpClient::TcpClient(TcpClient&& o) noexcept : fd_(o.fd_), peer_(o.peer_), name_(std::move(o.name_)), buffer_(std::move(o.buffer_)) {
  o.fd_ = -1;
}

TcpClient& TcpClient::operator=(TcpClient&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    o.fd_ = -1;
    peer_ = o.peer_;
    name_ = std::move(o.name_);
    buffer_ = std::move(o.buffer_);
  }
  return *this;
}

TcpClient::~TcpClient() {
  if (fd_ >= 0) ::close(fd_);
}

Status TcpClient::send(std::span<const uint8_t> bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{fd_, POLLOUT, 0};
      if (::poll(&p, 1, 1000) <= 0) return Error::failed(name_ + ": " + peer_.to_string() + " stopped reading");
    } else {
      return Error::failed(name_ + ": connection to " + peer_.to_string() + " lost: " + std::strerror(errno));
    }
  }
  return Ok{};
}

bool TcpClient::wait_readable(int timeout_ms) const {
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms) > 0;
}

Expected<std::span<const uint8_t>> TcpClient::receive() {
  for (;;) {
    const ssize_t n = ::recv(fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT);
    if (n > 0) return std::span<const uint8_t>(buffer_.data(), static_cast<std::size_t>(n));
    if (n == 0) return Error::failed(name_ + ": " + peer_.to_string() + " closed the connection");
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return std::span<const uint8_t>{};
    return Error::failed(name_ + ": connection to " + peer_.to_string() + " lost: " + std::strerror(errno));
  }
}

}  // namespace hitl::net
