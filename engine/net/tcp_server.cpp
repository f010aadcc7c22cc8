#include "engine/net/tcp_server.h"

#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace hitl::net {

Expected<TcpServer> TcpServer::listen(const std::string& bind_address, uint16_t port, const std::string& name) {
  auto addr = SocketAddress::resolve(bind_address, port);
  if (!addr) return addr.error().prefixed(name + ": bad address '" + bind_address + "': ");
  const int fd = ::socket(addr->family(), SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return Error::unavailable(name + ": cannot create a TCP socket: " + std::strerror(errno));
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (::bind(fd, addr->get(), addr->length()) != 0 || ::listen(fd, 1) != 0) {
    const int err = errno;
    ::close(fd);
    return Error::unavailable(name + ": cannot listen on TCP " + addr->to_string() + ": " +
                 (err == EADDRINUSE ? "address already in use: another process listens there (find it with: ss -tlpn 'sport = :" +
                                          std::to_string(port) + "')"
                                    : std::string(std::strerror(err))));
  }
  sockaddr_storage local{};
  socklen_t len = sizeof local;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len);
  return TcpServer(fd, SocketAddress(reinterpret_cast<sockaddr*>(&local), len), name);
}

TcpServer::TcpServer(int fd, SocketAddress local, std::string name)
    : listen_fd_(fd), local_(local), name_(std::move(name)), buffer_(65536) {}

TcpServer::TcpServer(TcpServer&& o) noexcept
    : listen_fd_(o.listen_fd_), client_fd_(o.client_fd_), local_(o.local_), client_addr_(o.client_addr_),
      name_(std::move(o.name_)), buffer_(std::move(o.buffer_)) {
  o.listen_fd_ = o.client_fd_ = -1;
}

TcpServer& TcpServer::operator=(TcpServer&& o) noexcept {
  if (this != &o) {
    this->~TcpServer();
    new (this) TcpServer(std::move(o));
  }
  return *this;
}

TcpServer::~TcpServer() {
  if (client_fd_ >= 0) ::close(client_fd_);
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

void TcpServer::drop_client() {
  if (client_fd_ >= 0) ::close(client_fd_);
  client_fd_ = -1;
}

bool TcpServer::accept_client(int timeout_ms) {
  if (client_fd_ >= 0) return true;
  pollfd p{listen_fd_, POLLIN, 0};
  if (::poll(&p, 1, timeout_ms) <= 0) return false;
  sockaddr_storage from{};
  socklen_t len = sizeof from;
  const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&from), &len, SOCK_CLOEXEC | SOCK_NONBLOCK);
  if (fd < 0) return false;
  const int on = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  client_fd_ = fd;
  client_addr_ = SocketAddress(reinterpret_cast<sockaddr*>(&from), len);
  return true;
}

Expected<std::span<const uint8_t>> TcpServer::receive() {
  if (client_fd_ < 0) return Error::failed(name_ + ": no client connected");
  for (;;) {
    const ssize_t n = ::recv(client_fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT);
    if (n > 0) return std::span<const uint8_t>(buffer_.data(), static_cast<std::size_t>(n));
    if (n == 0) {
      drop_client();
      return Error::failed(name_ + ": the client closed the connection");
    }
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return std::span<const uint8_t>{};
    const std::string why = std::strerror(errno);
    drop_client();
    return Error::failed(name_ + ": connection lost: " + why);
  }
}

Status TcpServer::send(std::span<const uint8_t> bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    if (client_fd_ < 0) return Error::failed(name_ + ": no client connected");
    const ssize_t n = ::send(client_fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      pollfd p{client_fd_, POLLOUT, 0};
      if (::poll(&p, 1, 1000) <= 0) return Error::failed(name_ + ": the client stopped reading");
      continue;
    }
    const std::string why = n < 0 ? std::strerror(errno) : "closed";
    drop_client();
    return Error::failed(name_ + ": connection lost: " + why);
  }
  return Ok{};
}

bool TcpServer::wait_readable(int timeout_ms) const {
  if (client_fd_ < 0) return false;
  pollfd p{client_fd_, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms) > 0;
}

}  // namespace hitl::net
