#include "target/adb-relay/relay.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "base/common/clock.h"

namespace hitl::adb {
namespace {

std::string address_text(const sockaddr_in& a) {
  char host[INET_ADDRSTRLEN] = "?";
  ::inet_ntop(AF_INET, &a.sin_addr, host, sizeof host);
  return std::string(host) + ":" + std::to_string(ntohs(a.sin_port));
}

bool fill_address(const std::string& host, uint16_t port, sockaddr_in* out) {
  *out = sockaddr_in{};
  out->sin_family = AF_INET;
  out->sin_port = htons(port);
  return ::inet_pton(AF_INET, host.c_str(), &out->sin_addr) == 1;
}

/// A UDP socket bound to 127.0.0.1:source_port (0: any) and connected to 127.0.0.1:target_port,
/// so that it hears the board's port only. -1 and `error` on failure.
int open_channel_socket(Channel channel, uint16_t target_port, uint16_t source_port, std::string* error) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) {
    *error = std::string("cannot create a UDP socket: ") + std::strerror(errno);
    return -1;
  }
  sockaddr_in local{};
  fill_address("127.0.0.1", source_port, &local);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
    *error = std::string(to_string(channel)) + " channel: cannot bind UDP 127.0.0.1:" + std::to_string(source_port) + ": " +
             std::strerror(errno) + (errno == EADDRINUSE ? " (another program sends from it; choose another --" +
                                                               std::string(channel == Channel::Hil ? "hil" : "gcs") +
                                                               "-source-port)"
                                                         : "");
    ::close(fd);
    return -1;
  }
  sockaddr_in target{};
  fill_address("127.0.0.1", target_port, &target);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&target), sizeof target) != 0) {
    *error = std::string(to_string(channel)) + " channel: cannot address UDP 127.0.0.1:" + std::to_string(target_port) +
             ": " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

class Relay::HostEvents : public FramedStream::Events {
 public:
  explicit HostEvents(Relay& relay) : relay_(relay) {}
  std::string on_hello(const Hello& hello) override {
    if (hello.version != kProtocolVersion) {
      std::lock_guard<std::mutex> lock(relay_.stats_mutex_);
      ++relay_.stats_.version_mismatches;
      return "the host speaks tunnel protocol version " + std::to_string(hello.version) + ", this relay speaks version " +
             std::to_string(kProtocolVersion) + " (use the hitl-adb-relay of the same hitl release)";
    }
    relay_.host_hello_deadline_ms_ = 0;
    {
      std::lock_guard<std::mutex> lock(relay_.stats_mutex_);
      ++relay_.stats_.connections;
      relay_.stats_.host_connected = true;
    }
    for (bool& logged : relay_.refused_logged_) logged = false;
    relay_.log_("host connected from " + relay_.host_name_ + " (tunnel protocol " + std::to_string(hello.version) + ")");
    return {};
  }
  void on_frame(Channel channel, const uint8_t* payload, std::size_t size) override {
    if (channel != Channel::Control) {
      relay_.send_to_board(channel, payload, size);
      return;
    }
    const auto control = parse_control(payload, size);
    if (!control) {
      bad_control_ = true;
      return;
    }
    if (control->type == ControlType::Ping) relay_.host_->queue_control({ControlType::Pong, control->value});
  }
  bool bad_control_ = false;

 private:
  Relay& relay_;
};

std::unique_ptr<Relay> Relay::open(const RelayConfig& config, Log log, std::string* error) {
  std::unique_ptr<Relay> relay(new Relay(config, std::move(log)));
  sockaddr_in listen_addr{};
  if (!fill_address(config.bind_address, config.tcp_port, &listen_addr)) {
    *error = "--bind: '" + config.bind_address + "' is not an IPv4 address";
    return nullptr;
  }
  relay->listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (relay->listen_fd_ < 0) {
    *error = std::string("cannot create a TCP socket: ") + std::strerror(errno);
    return nullptr;
  }
  const int on = 1;
  ::setsockopt(relay->listen_fd_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (::bind(relay->listen_fd_, reinterpret_cast<const sockaddr*>(&listen_addr), sizeof listen_addr) != 0 ||
      ::listen(relay->listen_fd_, 4) != 0) {
    const int err = errno;
    *error = "cannot listen on TCP " + address_text(listen_addr) + ": " + std::strerror(err) +
             (err == EADDRINUSE ? " (is another hitl-adb-relay running? --port chooses another port)" : "");
    return nullptr;
  }
  socklen_t len = sizeof listen_addr;
  ::getsockname(relay->listen_fd_, reinterpret_cast<sockaddr*>(&listen_addr), &len);
  relay->tcp_port_ = ntohs(listen_addr.sin_port);
  const struct {
    Channel channel;
    uint16_t target, source;
  } channels[] = {{Channel::Hil, config.hil_port, config.hil_source_port},
                  {Channel::Vio, config.vio_port, 0},
                  {Channel::Gcs, config.gcs_port, config.gcs_source_port}};
  for (const auto& c : channels) {
    const int fd = open_channel_socket(c.channel, c.target, c.source, error);
    if (fd < 0) return nullptr;
    relay->udp_fd_[index_of(c.channel)] = fd;
    relay->target_port_[index_of(c.channel)] = c.target;
  }
  return relay;
}

Relay::Relay(const RelayConfig& config, Log log) : config_(config), log_(std::move(log)), udp_buffer_(65536) {}

Relay::~Relay() {
  host_.reset();
  if (listen_fd_ >= 0) ::close(listen_fd_);
  for (int fd : udp_fd_)
    if (fd >= 0) ::close(fd);
}

std::string Relay::listen_address() const { return config_.bind_address + ":" + std::to_string(tcp_port_); }

RelayStats Relay::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void Relay::accept_host() {
  sockaddr_in from{};
  socklen_t len = sizeof from;
  const int fd = ::accept4(listen_fd_, reinterpret_cast<sockaddr*>(&from), &len, SOCK_CLOEXEC | SOCK_NONBLOCK);
  if (fd < 0) return;  // gone before we took it, or out of descriptors: the next poll tries again
  const std::string name = address_text(from);
  if (host_) {
    log_("a new host connection from " + name + " replaces the one from " + host_name_);
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.replaced;
    stats_.host_connected = false;
  }
  host_ = std::make_unique<FramedStream>(fd);
  host_name_ = name;
  host_->queue_hello();
  host_hello_deadline_ms_ = monotonic_ms() + config_.hello_timeout_ms;
  (void)host_->flush();
}

void Relay::drop_host(const std::string& why, bool malformed) {
  if (!host_) return;
  (void)host_->flush();  // our hello tells a mismatched host which version we speak
  log_((malformed ? "dropping the host connection from " : "host ") + host_name_ + (malformed ? ": " : " disconnected: ") + why);
  host_.reset();
  host_hello_deadline_ms_ = 0;
  std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_.host_connected = false;
  if (malformed) ++stats_.malformed;
}

void Relay::read_host() {
  HostEvents events(*this);
  const auto result = host_->read(events);
  if (events.bad_control_) {
    drop_host("malformed control message on channel 0", true);
    return;
  }
  if (result == FramedStream::ReadResult::Closed) drop_host(host_->error(), false);
  else if (result == FramedStream::ReadResult::Failed) drop_host(host_->error(), true);
}

void Relay::send_to_board(Channel channel, const uint8_t* payload, std::size_t size) {
  const std::size_t i = index_of(channel);
  const ssize_t n = ::send(udp_fd_[i], payload, size, MSG_DONTWAIT);
  std::lock_guard<std::mutex> lock(stats_mutex_);
  if (n == static_cast<ssize_t>(size)) {
    ++stats_.channels[i].to_board;
    return;
  }
  ++stats_.channels[i].send_errors;
  if (!refused_logged_[i] || config_.verbose) {
    refused_logged_[i] = true;
    log_(std::string(to_string(channel)) + " channel: sending to 127.0.0.1:" + std::to_string(target_port_[i]) + " failed: " +
         (n < 0 ? std::strerror(errno) : "short send") +
         (n < 0 && errno == ECONNREFUSED ? " (nothing listens there yet)" : ""));
  }
}

void Relay::read_board(Channel channel) {
  const std::size_t i = index_of(channel);
  for (int reads = 0; reads < 64; ++reads) {
    const ssize_t n = ::recv(udp_fd_[i], udp_buffer_.data(), udp_buffer_.size(), MSG_DONTWAIT | MSG_TRUNC);
    if (n < 0) {
      if (errno == EINTR) continue;
      // ECONNREFUSED: an earlier send found nothing listening (reported by send_to_board).
      return;
    }
    const std::size_t size = static_cast<std::size_t>(n);
    std::lock_guard<std::mutex> lock(stats_mutex_);
    auto& c = stats_.channels[i];
    if (!host_ || !host_->peer_hello()) {
      ++c.dropped_no_host;
      continue;
    }
    if (size > kMaxDatagram_bytes || size > udp_buffer_.size()) {
      ++c.dropped_too_large;
      if (config_.verbose) log_(std::string(to_string(channel)) + " channel: dropped a " + std::to_string(size) + "-byte datagram (over " + std::to_string(kMaxDatagram_bytes) + ")");
      continue;
    }
    switch (host_->queue(channel, udp_buffer_.data(), size)) {
      case FramedStream::Queued::Yes: ++c.from_board; break;
      case FramedStream::Queued::TooLarge: ++c.dropped_too_large; break;
      case FramedStream::Queued::BacklogFull: ++c.dropped_backlog; break;
    }
  }
}

void Relay::log_counters() {
  const RelayStats s = stats();
  std::string line = s.host_connected ? "host " + host_name_ + ":" : "no host:";
  for (Channel c : kDataChannels) {
    const auto& k = s.channels[index_of(c)];
    line += std::string(" ") + to_string(c) + " to board " + std::to_string(k.to_board) + ", from board " +
            std::to_string(k.from_board);
    const uint64_t dropped = k.dropped_no_host + k.dropped_backlog + k.dropped_too_large;
    if (dropped) line += " (dropped " + std::to_string(dropped) + ")";
    if (k.send_errors) line += " (send errors " + std::to_string(k.send_errors) + ")";
    line += ";";
  }
  line.pop_back();
  log_(line);
}

void Relay::run(const std::atomic<bool>& stop) {
  log_("listening on TCP " + listen_address() + "; HIL -> 127.0.0.1:" + std::to_string(config_.hil_port) +
       ", VIO -> 127.0.0.1:" + std::to_string(config_.vio_port) + ", GCS -> 127.0.0.1:" + std::to_string(config_.gcs_port) +
       " (tunnel protocol " + std::to_string(kProtocolVersion) + ")");
  int64_t next_counters_ms = monotonic_ms() + 10000;
  while (!stop.load()) {
    pollfd fds[2 + 3];
    nfds_t n = 0;
    fds[n++] = {listen_fd_, POLLIN, 0};
    const nfds_t host_index = n;
    if (host_) fds[n++] = {host_->fd(), static_cast<short>(POLLIN | (host_->backlog() ? POLLOUT : 0)), 0};
    const nfds_t udp_index = n;
    for (Channel c : kDataChannels) fds[n++] = {udp_fd_[index_of(c)], POLLIN, 0};
    const int ready = ::poll(fds, n, 100);
    if (ready < 0 && errno != EINTR) {
      log_(std::string("poll failed: ") + std::strerror(errno));
      return;
    }
    const int64_t now_ms = monotonic_ms();
    if (ready > 0) {
      for (nfds_t k = 0; k < 3; ++k)
        if (fds[udp_index + k].revents & (POLLIN | POLLERR)) read_board(kDataChannels[k]);
      if (host_ && host_index < udp_index) {
        const short re = fds[host_index].revents;
        if (re & (POLLIN | POLLHUP | POLLERR)) read_host();
      }
      if (fds[0].revents & POLLIN) accept_host();
    }
    if (host_ && host_hello_deadline_ms_ && now_ms > host_hello_deadline_ms_)
      drop_host("no hello within " + std::to_string(config_.hello_timeout_ms) + " ms", true);
    if (host_ && host_->backlog()) {
      if (std::string error = host_->flush(); !error.empty()) drop_host(error, false);
    }
    if (config_.verbose && now_ms >= next_counters_ms) {
      log_counters();
      next_counters_ms = now_ms + 10000;
    }
  }
  if (host_) drop_host("the relay is stopping", false);
  log_("stopped");
}

}  // namespace hitl::adb
