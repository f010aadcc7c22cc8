#include "engine/net/tcp_hub_link.h"

#include <netinet/tcp.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "base/mavlink/frame_parser.h"

namespace hitl::net {

struct TcpHubLink::Client {
  int fd = -1;
  SocketAddress address;
  std::vector<uint8_t> pending;  ///< what the kernel did not take yet, in order
  std::unique_ptr<mavlink::FrameParser> parser;  ///< drain_from(): this client's stream
  bool said_slow = false;
  ~Client() {
    if (fd >= 0) ::close(fd);
  }
};

Expected<std::unique_ptr<TcpHubLink>> TcpHubLink::listen(const std::string& bind_address, uint16_t port, std::size_t max_clients,
                                                         const std::string& name) {
  auto addr = SocketAddress::resolve(bind_address, port);
  if (!addr) return addr.error().prefixed(name + ": bad address '" + bind_address + "': ");
  const int fd = ::socket(addr->family(), SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return Error::unavailable(name + ": cannot create a TCP socket: " + std::strerror(errno));
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (::bind(fd, addr->get(), addr->length()) != 0 || ::listen(fd, 16) != 0) {
    const int err = errno;
    ::close(fd);
    return Error::unavailable(name + ": cannot listen on TCP " + addr->to_string() + ": " +
                              (err == EADDRINUSE ? "address already in use: another process listens there (find it with: "
                                                   "ss -tlpn 'sport = :" + std::to_string(port) + "')"
                                                 : std::string(std::strerror(err))));
  }
  const int ep = ::epoll_create1(EPOLL_CLOEXEC);
  if (ep < 0) {
    ::close(fd);
    return Error::unavailable(name + ": cannot create an epoll descriptor: " + std::strerror(errno));
  }
  epoll_event ev{};
  ev.events = EPOLLIN;
  ev.data.fd = fd;
  ::epoll_ctl(ep, EPOLL_CTL_ADD, fd, &ev);
  sockaddr_storage local{};
  socklen_t len = sizeof local;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len);
  return std::unique_ptr<TcpHubLink>(
      new TcpHubLink(fd, ep, SocketAddress(reinterpret_cast<sockaddr*>(&local), len), std::max<std::size_t>(1, max_clients), name));
}

TcpHubLink::TcpHubLink(int listen_fd, int epoll_fd, SocketAddress local, std::size_t max_clients, const std::string& name)
    : Link(name), listen_fd_(listen_fd), epoll_fd_(epoll_fd), local_(local), max_clients_(max_clients), rx_buffer_(65536) {}

TcpHubLink::~TcpHubLink() {
  clients_.clear();
  if (epoll_fd_ >= 0) ::close(epoll_fd_);
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

std::optional<SocketAddress> TcpHubLink::peer() const {
  if (clients_.empty()) return std::nullopt;
  return clients_.back()->address;
}

void TcpHubLink::accept_waiting() {
  for (;;) {
    sockaddr_storage from{};
    socklen_t len = sizeof from;
    const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&from), &len, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0) return;  // none waiting (EAGAIN), or one that gave up already
    const SocketAddress address(reinterpret_cast<sockaddr*>(&from), len);
    if (clients_.size() >= max_clients_) {
      ::close(fd);
      ++stats_.send_errors;
      if (!said_full_) {
        said_full_ = true;
        say(name_ + ": refused " + address.to_string() + ": " + std::to_string(max_clients_) +
                " clients are connected, the most it takes (further ones are refused without a word)",
            Severity::Warning);
      }
      continue;
    }
    const int on = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = fd;
    ::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, fd, &ev);
    auto c = std::make_unique<Client>();
    c->fd = fd;
    c->address = address;
    clients_.push_back(std::move(c));
    ++stats_.connects;
    say(name_ + ": " + address.to_string() + " connected (" + std::to_string(clients_.size()) + " connected)", Severity::Info);
  }
}

void TcpHubLink::drop(std::size_t index, const std::string& why) {
  const std::string address = clients_[index]->address.to_string();
  ::epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, clients_[index]->fd, nullptr);
  clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(index));
  say(name_ + ": " + address + " " + why + " (" + std::to_string(clients_.size()) + " connected)", Severity::Info);
}

void TcpHubLink::maintain(double /*now_s*/) {
  accept_waiting();
  for (std::size_t i = 0; i < clients_.size();) {  // what a slow client could not take yet
    if (!clients_[i]->pending.empty() && !write(*clients_[i], {})) {
      drop(i, "connection lost");
      continue;
    }
    ++i;
  }
}

bool TcpHubLink::wait_readable(int timeout_ms) const {
  pollfd p{epoll_fd_, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms) > 0;
}

std::size_t TcpHubLink::read_some(std::size_t max_reads, const ChunkHandler& on_chunk) {
  accept_waiting();
  std::size_t reads = 0;
  for (std::size_t i = 0; i < clients_.size() && reads < max_reads;) {
    Client& c = *clients_[i];
    const ssize_t n = ::recv(c.fd, rx_buffer_.data(), rx_buffer_.size(), MSG_DONTWAIT);
    if (n > 0) {
      ++reads;
      ++stats_.datagrams_in;
      stats_.bytes_in += static_cast<std::size_t>(n);
      on_chunk(LinkChunk{{rx_buffer_.data(), static_cast<std::size_t>(n)}, c.address, /*whole_datagram=*/false});
      ++i;
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
      ++i;
      continue;
    }
    drop(i, n == 0 ? "disconnected" : std::string("connection lost: ") + std::strerror(errno));
  }
  return reads;
}

std::size_t TcpHubLink::drain_from(mavlink::FrameParser& parser, const SourcedFrameHandler& on_frame, std::size_t max_reads) {
  return read_some(max_reads, [&](const LinkChunk& chunk) {
    for (auto& c : clients_) {
      if (c->address != chunk.from) continue;
      if (!c->parser) c->parser = std::make_unique<mavlink::FrameParser>(parser.messages());
      c->parser->feed(chunk.bytes, [&](const mavlink::Frame& f) { on_frame(f, chunk.from); });
      return;
    }
  });
}

bool TcpHubLink::write(Client& c, std::span<const uint8_t> bytes) {
  if (!c.pending.empty()) {  // first what waits, so the stream stays in order
    const ssize_t n = ::send(c.fd, c.pending.data(), c.pending.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return false;
    if (n > 0) c.pending.erase(c.pending.begin(), c.pending.begin() + n);
  }
  if (bytes.empty()) return true;
  std::size_t sent = 0;
  if (c.pending.empty()) {
    const ssize_t n = ::send(c.fd, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return false;
    if (n > 0) sent = static_cast<std::size_t>(n);
  }
  if (sent == bytes.size()) {
    ++stats_.datagrams_out;
    stats_.bytes_out += bytes.size();
    return true;
  }
  const auto rest = bytes.subspan(sent);
  if (sent == 0 && c.pending.size() + rest.size() > kMaxPending_bytes) {  // dropped whole: the stream stays frames
    ++stats_.send_errors;
    if (!c.said_slow) {
      c.said_slow = true;
      say(name_ + ": " + c.address.to_string() + " reads slower than frames come; frames it has no room for are dropped (counted)",
          Severity::Warning);
    }
    return true;
  }
  c.pending.insert(c.pending.end(), rest.begin(), rest.end());  // a frame begun is finished: at most one frame over the bound
  ++stats_.datagrams_out;
  stats_.bytes_out += bytes.size();
  return true;
}

Status TcpHubLink::send_to_peers(std::span<const uint8_t> bytes, const std::optional<SocketAddress>& except,
                                 std::span<const SocketAddress> only) {
  for (std::size_t i = 0; i < clients_.size();) {
    Client& c = *clients_[i];
    const bool skip = (except && c.address == *except) ||
                      (!only.empty() && std::find(only.begin(), only.end(), c.address) == only.end());
    if (!skip && !write(c, bytes)) {
      drop(i, "connection lost");
      continue;
    }
    ++i;
  }
  return Ok{};
}

Status TcpHubLink::send(std::span<const uint8_t> bytes) { return send_to_peers(bytes, std::nullopt, {}); }

Status TcpHubLink::flush() {
  if (tx_.empty()) return Ok{};
  std::vector<uint8_t> bytes;
  bytes.swap(tx_);
  return send(bytes);
}

}  // namespace hitl::net
