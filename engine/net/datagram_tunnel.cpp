#include "engine/net/datagram_tunnel.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "base/common/clock.h"

namespace hitl::net {
namespace {

/// The handshake's view of the stream: the relay's hello, compared with ours.
class HandshakeEvents : public adb::FramedStream::Events {
 public:
  std::string on_hello(const adb::Hello& hello) override {
    if (hello.version == adb::kProtocolVersion) return {};
    return "hitl-adb-relay on the board speaks tunnel protocol version " + std::to_string(hello.version) +
           ", this hitl speaks version " + std::to_string(adb::kProtocolVersion) +
           ": stop it (adb shell pkill -x hitl-adb-relay) and install the voxl-hitl-px4-scripts package of this hitl "
           "release on the board (or remove /usr/bin/hitl-adb-relay there, and hitl pushes its own)";
  }
  // A datagram the relay sent right after its hello is dropped: the pump is not running yet.
  void on_frame(adb::Channel, const uint8_t*, std::size_t) override {}
};

}  // namespace

RelayConnection connect_to_relay(const SocketAddress& address, int timeout_ms) {
  RelayConnection r;
  const std::string where = "hitl-adb-relay through TCP " + address.to_string();
  const int fd = ::socket(address.family(), SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) {
    r.error = "cannot create a TCP socket: " + std::string(std::strerror(errno));
    return r;
  }
  const int64_t deadline_ms = monotonic_ms() + timeout_ms;
  if (::connect(fd, address.get(), address.length()) != 0 && errno != EINPROGRESS) {
    r.relay_absent = errno == ECONNREFUSED;
    r.error = "cannot connect to " + where + ": " + std::strerror(errno);
    ::close(fd);
    return r;
  }
  pollfd p{fd, POLLOUT, 0};
  int err = 0;
  socklen_t len = sizeof err;
  if (::poll(&p, 1, timeout_ms) <= 0 || ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0 || err != 0) {
    r.relay_absent = err == ECONNREFUSED;
    r.error = "cannot connect to " + where + ": " + (err ? std::strerror(err) : "timed out");
    ::close(fd);
    return r;
  }
  auto stream = std::make_unique<adb::FramedStream>(fd);
  stream->queue_hello();
  HandshakeEvents events;
  while (!stream->peer_hello()) {
    if (auto e = stream->flush(); !e.empty()) {
      r.relay_absent = stream->bytes_in() == 0;
      r.error = where + ": " + e;
      return r;
    }
    const int64_t left_ms = deadline_ms - monotonic_ms();
    if (left_ms <= 0) {
      r.error = where + ": no hello within " + std::to_string(timeout_ms) + " ms (something else listens there?)";
      return r;
    }
    pollfd q{stream->fd(), static_cast<short>(POLLIN | (stream->backlog() ? POLLOUT : 0)), 0};
    ::poll(&q, 1, static_cast<int>(left_ms));
    const auto result = stream->read(events);
    if (result == adb::FramedStream::ReadResult::Closed) {
      // adb accepts the local connection, then closes it when nothing listens on the board's port.
      r.relay_absent = stream->bytes_in() == 0;
      r.error = where + ": " + (r.relay_absent ? "closed at once (no relay listening on the board)" : stream->error());
      return r;
    }
    if (result == adb::FramedStream::ReadResult::Failed) {
      r.error = where + ": " + stream->error();
      return r;
    }
  }
  if (auto e = stream->flush(); !e.empty()) {
    r.error = where + ": " + e;
    return r;
  }
  r.stream = std::move(stream);
  return r;
}

class DatagramTunnel::StreamEvents : public adb::FramedStream::Events {
 public:
  explicit StreamEvents(DatagramTunnel& t) : t_(t) {}
  std::string on_hello(const adb::Hello&) override { return "a second hello on the stream"; }
  void on_frame(adb::Channel channel, const uint8_t* payload, std::size_t size) override {
    if (channel == adb::Channel::Control) {
      const auto control = adb::parse_control(payload, size);
      if (!control) {
        malformed_control = true;
        return;
      }
      if (control->type == adb::ControlType::Pong) {
        const double rtt_ms = static_cast<double>(monotonic_ns() - control->value) * 1e-6;
        std::lock_guard<std::mutex> lock(t_.stats_mutex_);
        t_.stats_.rtt_ms = rtt_ms;
        if (rtt_ms > t_.stats_.rtt_max_ms) t_.stats_.rtt_max_ms = rtt_ms;
      }
      return;
    }
    auto& local = *t_.local_[adb::index_of(channel)];
    const bool sent = local.partner() && local.send({payload, size}).ok();
    std::lock_guard<std::mutex> lock(t_.stats_mutex_);
    auto& c = t_.stats_.channels[adb::index_of(channel)];
    if (sent) {
      ++c.from_board;
      c.bytes_from_board += size;
    } else {
      ++c.dropped_no_client;
    }
  }
  bool malformed_control = false;

 private:
  DatagramTunnel& t_;
};

Expected<std::unique_ptr<DatagramTunnel>> DatagramTunnel::open(const Config& config, Connector connector) {
  std::unique_ptr<DatagramTunnel> t(new DatagramTunnel(config, std::move(connector)));
  for (adb::Channel c : adb::kDataChannels) {
    UdpEndpoint::Config ec;
    ec.name = std::string("adb tunnel ") + adb::to_string(c) + " endpoint";
    ec.bind_address = config.local_address;
    ec.bind_port = 0;
    ec.policy = PartnerPolicy::LastSender;
    auto ep = UdpEndpoint::open(ec);
    if (!ep) return ep.error();
    t->local_address_[adb::index_of(c)] = ep->local_address();
    t->local_[adb::index_of(c)].emplace(std::move(ep.value()));
  }
  t->wake_fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (t->wake_fd_ < 0) return Error::unavailable("adb tunnel: cannot create an eventfd: " + std::string(std::strerror(errno)));
  auto stream = t->connector_();
  if (!stream) return stream.error();
  t->stream_ = std::move(stream.value());
  t->last_rx_ms_ = monotonic_ms();
  t->last_bytes_in_ = t->stream_->bytes_in();
  {
    std::lock_guard<std::mutex> lock(t->stats_mutex_);
    t->stats_.connected = true;
    t->stats_.connects = 1;
  }
  t->thread_ = std::thread(&DatagramTunnel::pump, t.get());
  return t;
}

DatagramTunnel::DatagramTunnel(const Config& config, Connector connector)
    : config_(config), connector_(std::move(connector)) {}

DatagramTunnel::~DatagramTunnel() {
  stop_.store(true);
  if (wake_fd_ >= 0) {
    const uint64_t one = 1;
    (void)!::write(wake_fd_, &one, sizeof one);
  }
  if (thread_.joinable()) thread_.join();
  stream_.reset();
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

const SocketAddress& DatagramTunnel::local_endpoint(adb::Channel channel) const { return local_address_[adb::index_of(channel)]; }

TunnelStats DatagramTunnel::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void DatagramTunnel::emit(const std::string& line) const {
  if (config_.on_event) config_.on_event(line);
}

void DatagramTunnel::lose_link(const std::string& why) {
  stream_.reset();
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.connected = false;
    ++stats_.link_losses;
    stats_.last_error = why;
  }
  emit("adb tunnel: link to the relay lost (" + why + "); reconnecting");
}

void DatagramTunnel::read_local(adb::Channel channel) {
  auto& local = *local_[adb::index_of(channel)];
  for (int reads = 0; reads < 64; ++reads) {
    auto d = local.receive();
    if (!d) return;
    std::lock_guard<std::mutex> lock(stats_mutex_);
    auto& c = stats_.channels[adb::index_of(channel)];
    if (!stream_) {
      ++c.dropped_no_link;
      continue;
    }
    switch (stream_->queue(channel, d->bytes.data(), d->bytes.size())) {
      case adb::FramedStream::Queued::Yes:
        ++c.to_board;
        c.bytes_to_board += d->bytes.size();
        break;
      case adb::FramedStream::Queued::TooLarge: ++c.dropped_too_large; break;
      case adb::FramedStream::Queued::BacklogFull: ++c.dropped_backlog; break;
    }
  }
}

void DatagramTunnel::pump() {
  int64_t next_ping_ms = monotonic_ms();
  int64_t next_attempt_ms = 0;
  int64_t next_failure_report_ms = 0;
  while (!stop_.load()) {
    int64_t now_ms = monotonic_ms();
    if (!stream_ && now_ms >= next_attempt_ms) {
      auto stream = connector_();
      now_ms = monotonic_ms();
      if (stream) {
        stream_ = std::move(stream.value());
        last_rx_ms_ = now_ms;
        last_bytes_in_ = stream_->bytes_in();
        next_ping_ms = now_ms;
        {
          std::lock_guard<std::mutex> lock(stats_mutex_);
          stats_.connected = true;
          ++stats_.connects;
        }
        emit("adb tunnel: link to the relay restored");
      } else {
        {
          std::lock_guard<std::mutex> lock(stats_mutex_);
          stats_.last_error = stream.error().message;
        }
        if (now_ms >= next_failure_report_ms) {  // once every 10 s while it lasts
          emit("adb tunnel: still no link: " + stream.error().message);
          next_failure_report_ms = now_ms + 10000;
        }
        next_attempt_ms = now_ms + config_.reconnect_period_ms;
      }
    }
    pollfd fds[2 + adb::kChannelCount];
    nfds_t n = 0;
    fds[n++] = {wake_fd_, POLLIN, 0};
    const nfds_t local_index = n;
    for (adb::Channel c : adb::kDataChannels) fds[n++] = {local_[adb::index_of(c)]->fd(), POLLIN, 0};
    const nfds_t stream_index = n;
    if (stream_) fds[n++] = {stream_->fd(), static_cast<short>(POLLIN | (stream_->backlog() ? POLLOUT : 0)), 0};
    const int ready = ::poll(fds, n, 100);
    if (stop_.load()) break;
    if (ready > 0) {
      for (nfds_t k = 0; k < 3; ++k)
        if (fds[local_index + k].revents & POLLIN) read_local(adb::kDataChannels[k]);
      if (stream_ && stream_index < n && (fds[stream_index].revents & (POLLIN | POLLHUP | POLLERR))) {
        StreamEvents events(*this);
        const auto result = stream_->read(events);
        if (events.malformed_control) lose_link("malformed control message from the relay");
        else if (result != adb::FramedStream::ReadResult::Open) lose_link(stream_->error());
      }
    }
    now_ms = monotonic_ms();
    if (stream_) {
      if (stream_->bytes_in() != last_bytes_in_) {
        last_bytes_in_ = stream_->bytes_in();
        last_rx_ms_ = now_ms;
      }
      if (now_ms >= next_ping_ms) {
        stream_->queue_control({adb::ControlType::Ping, monotonic_ns()});
        next_ping_ms = now_ms + config_.ping_period_ms;
      }
      if (now_ms - last_rx_ms_ > config_.link_timeout_ms) {
        lose_link("no answer from the relay for " + std::to_string(config_.link_timeout_ms) + " ms");
      } else if (auto e = stream_->flush(); !e.empty()) {
        lose_link(e);
      }
    }
  }
}

}  // namespace hitl::net
