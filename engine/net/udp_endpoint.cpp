#include "engine/net/udp_endpoint.h"

#include "base/common/clock.h"
#include "engine/net/send_error.h"
#include <fcntl.h>
#include <linux/sock_diag.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

namespace hitl::net {
namespace {

std::string bind_hint(int err, const std::string& where) {
  switch (err) {
    case EADDRINUSE:
      return "address already in use: another process is bound there (find it with: ss -ulpn 'sport = :" +
             where.substr(where.rfind(':') + 1) + "')";
    case EADDRNOTAVAIL: return "that address is not on any interface of this machine";
    case EACCES: return "permission denied (ports below 1024 need privileges)";
    default: return std::strerror(err);
  }
}

}  // namespace

Expected<UdpEndpoint> UdpEndpoint::open(const Config& config) {
  auto bind_addr = SocketAddress::resolve(config.bind_address, config.bind_port);
  if (!bind_addr) return bind_addr.error().prefixed(config.name + ": bad bind address '" + config.bind_address + "': ");
  const int fd = ::socket(bind_addr->family(), SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) return Error::unavailable(config.name + ": cannot create a UDP socket: " + std::strerror(errno));
  const int on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
  ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on);  // the kernel's receive drops, with each datagram
  if (config.receive_buffer_bytes > 0)
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &config.receive_buffer_bytes, sizeof config.receive_buffer_bytes);
  if (config.send_buffer_bytes > 0)
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &config.send_buffer_bytes, sizeof config.send_buffer_bytes);
  if (::bind(fd, bind_addr->get(), bind_addr->length()) != 0) {
    const int err = errno;
    ::close(fd);
    const std::string where = bind_addr->to_string();
    return Error::unavailable(config.name + ": cannot bind UDP " + where + ": " + bind_hint(err, where));
  }
  sockaddr_storage local{};
  socklen_t len = sizeof local;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &len);
  return UdpEndpoint(fd, config, SocketAddress(reinterpret_cast<sockaddr*>(&local), len));
}

UdpEndpoint::UdpEndpoint(int fd, Config config, SocketAddress local)
    : fd_(fd), config_(std::move(config)), local_(local), partner_(config_.peer), rx_buffer_(65536) {}

UdpEndpoint::UdpEndpoint(UdpEndpoint&& other) noexcept
    : fd_(other.fd_),
      config_(std::move(other.config_)),
      local_(other.local_),
      partner_(other.partner_),
      locked_(other.locked_),
      stats_(other.stats_),
      last_rxq_ovfl_(other.last_rxq_ovfl_),
      rx_buffer_(std::move(other.rx_buffer_)),
      tx_batch_(std::move(other.tx_batch_)) {
  other.fd_ = -1;
}

UdpEndpoint& UdpEndpoint::operator=(UdpEndpoint&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = other.fd_;
    other.fd_ = -1;
    config_ = std::move(other.config_);
    local_ = other.local_;
    partner_ = other.partner_;
    locked_ = other.locked_;
    stats_ = other.stats_;
    last_rxq_ovfl_ = other.last_rxq_ovfl_;
    rx_buffer_ = std::move(other.rx_buffer_);
    tx_batch_ = std::move(other.tx_batch_);
  }
  return *this;
}

UdpEndpoint::~UdpEndpoint() {
  if (fd_ >= 0) ::close(fd_);
}

void UdpEndpoint::learn(const SocketAddress& from) {
  switch (config_.policy) {
    case PartnerPolicy::Fixed: return;
    case PartnerPolicy::LastSender:
      if (!partner_ || *partner_ != from) {
        partner_ = from;
        ++stats_.partner_changes;
      }
      return;
    case PartnerPolicy::FirstSender:
      if (!locked_) {
        partner_ = from;
        locked_ = true;
        ++stats_.partner_changes;
      }
      return;
  }
}

std::optional<Datagram> UdpEndpoint::receive() {
  sockaddr_storage from{};
  iovec iov{rx_buffer_.data(), rx_buffer_.size()};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(uint32_t))];
  msghdr msg{};
  msg.msg_name = &from;
  msg.msg_namelen = sizeof from;
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof control;
  for (;;) {
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
    if (n < 0) {
      if (errno == EINTR) continue;
      // EAGAIN: nothing waiting. ECONNREFUSED: an ICMP port-unreachable for an earlier send; not data.
      if (errno == ECONNREFUSED) continue;
      return std::nullopt;
    }
    Datagram d;
    d.bytes = std::span<const uint8_t>(rx_buffer_.data(), static_cast<std::size_t>(n));
    d.from = SocketAddress(reinterpret_cast<sockaddr*>(&from), msg.msg_namelen);
    d.rx_time_unix_ns = 0;
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c)) {
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec ts{};
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        d.rx_time_unix_ns = int64_t{ts.tv_sec} * 1000000000 + ts.tv_nsec;
      } else if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        uint32_t dropped = 0;  // the socket's running count: add what is new since the last datagram
        std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
        add_kernel_drops(dropped);
      }
    }
    if (d.rx_time_unix_ns == 0) d.rx_time_unix_ns = unix_time_ns();
    ++stats_.datagrams_in;
    stats_.bytes_in += static_cast<uint64_t>(n);
    learn(d.from);
    return d;
  }
}

bool UdpEndpoint::wait_readable(int timeout_ms) const {
  pollfd p{fd_, POLLIN, 0};
  return ::poll(&p, 1, timeout_ms) > 0 && (p.revents & POLLIN);
}

UdpEndpoint::BufferSizes UdpEndpoint::buffer_sizes() const {
  BufferSizes b;
  socklen_t len = sizeof b.receive_bytes;
  ::getsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &b.receive_bytes, &len);
  len = sizeof b.send_bytes;
  ::getsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &b.send_bytes, &len);
  return b;
}

namespace {

/// SO_MEMINFO's figures for the socket; false when the kernel does not give them.
bool read_meminfo(int fd, uint32_t (&out)[SK_MEMINFO_VARS]) {
  socklen_t len = sizeof out;
  return ::getsockopt(fd, SOL_SOCKET, SO_MEMINFO, out, &len) == 0 && len >= sizeof(uint32_t) * (SK_MEMINFO_DROPS + 1);
}

}  // namespace

void UdpEndpoint::poll_kernel_drops() {
  uint32_t m[SK_MEMINFO_VARS] = {};
  if (!read_meminfo(fd_, m)) return;
  add_kernel_drops(m[SK_MEMINFO_DROPS]);
}

void UdpEndpoint::add_kernel_drops(uint32_t running_count) {
  // A datagram's SO_RXQ_OVFL is the count when it was queued, older than what SO_MEMINFO said
  // since: only a count ahead of the last one adds (the count wraps at 2^32).
  const uint32_t ahead = running_count - last_rxq_ovfl_;
  if (static_cast<int32_t>(ahead) <= 0) return;
  stats_.kernel_rx_drops += ahead;
  last_rxq_ovfl_ = running_count;
}

std::size_t UdpEndpoint::receive_queue_bytes() const {
  uint32_t m[SK_MEMINFO_VARS] = {};
  return read_meminfo(fd_, m) ? m[SK_MEMINFO_RMEM_ALLOC] : 0;
}

void UdpEndpoint::set_receive_buffer(int bytes) {
  ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);
}

SendOutcome UdpEndpoint::try_send_to(const SocketAddress& to, std::span<const uint8_t> bytes) {
  for (;;) {
    const ssize_t n = ::sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT | MSG_NOSIGNAL, to.get(), to.length());
    if (n >= 0) {
      ++stats_.datagrams_out;
      stats_.bytes_out += static_cast<uint64_t>(n);
      return SendOutcome::Sent;
    }
    const int error = errno;
    if (error == EINTR) continue;
    if (error == EAGAIN || error == EWOULDBLOCK || error == ENOBUFS) return SendOutcome::WouldBlock;
    (void)refused(to, error);
    return SendOutcome::Refused;
  }
}

Status UdpEndpoint::send_to(const SocketAddress& to, std::span<const uint8_t> bytes) {
  for (;;) {
    const ssize_t n = ::sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT | MSG_NOSIGNAL, to.get(), to.length());
    if (n >= 0) {
      ++stats_.datagrams_out;
      stats_.bytes_out += static_cast<uint64_t>(n);
      return Ok{};
    }
    const int error = errno;
    if (error == EINTR) continue;
    return refused(to, error);
  }
}

Error UdpEndpoint::refused(const SocketAddress& to, int error) {
  ++stats_.send_errors;
  stats_.last_send_errno = error;
  std::string text = config_.name + ": " + describe_send_error(error, local_, to);
  if (std::find(failed_destinations_.begin(), failed_destinations_.end(), to) == failed_destinations_.end()) {
    failed_destinations_.push_back(to);
    unreported_send_errors_.push_back(text);
  }
  return Error::failed(std::move(text));
}

Status UdpEndpoint::send(std::span<const uint8_t> bytes) {
  if (!partner_) return Error::failed(config_.name + ": no partner to send to yet");
  return send_to(*partner_, bytes);
}

Status UdpEndpoint::queue(std::span<const uint8_t> frame) {
  Status st = Ok{};
  if (!tx_batch_.empty() && tx_batch_.size() + frame.size() > kMaxDatagram) st = flush();
  tx_batch_.insert(tx_batch_.end(), frame.begin(), frame.end());
  return st;
}

std::vector<std::string> UdpEndpoint::take_send_errors() {
  std::vector<std::string> out;
  out.swap(unreported_send_errors_);
  return out;
}

Status UdpEndpoint::flush() {
  if (tx_batch_.empty()) return Ok{};
  auto st = send(tx_batch_);
  tx_batch_.clear();
  return st;
}

}  // namespace hitl::net
