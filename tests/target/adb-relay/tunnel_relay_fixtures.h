// What the tunnel relay tests share: the board's three UDP ports, Relay::run on a thread with its
// log, the host's DatagramTunnel opened on the relay, a raw TCP client for what a well-behaved host
// never sends, and waiting on sockets and conditions.
#pragma once

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "engine/net/datagram_tunnel.h"
#include "engine/net/udp_endpoint.h"
#include "target/adb-relay/relay.h"
#include "tests/support/loopback.h"

namespace hitl::relay_test {

using namespace std::chrono_literals;
using adb::Channel;

inline bool eventually(const std::function<bool()>& done, std::chrono::milliseconds timeout = 10s) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return done();
}

inline std::vector<uint8_t> text(const std::string& s) { return {s.begin(), s.end()}; }

inline net::UdpEndpoint open_udp(uint16_t port = 0) {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.bind_port = port;
  c.policy = net::PartnerPolicy::LastSender;
  return std::move(net::UdpEndpoint::open(c).value());
}

/// Waits for one datagram on `ep`; its text ("" on timeout).
inline std::string receive_text(net::UdpEndpoint& ep, std::chrono::milliseconds timeout = 5s, net::SocketAddress* from = nullptr) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (auto d = ep.receive()) {
      if (from) *from = d->from;
      return std::string(d->bytes.begin(), d->bytes.end());
    }
    ep.wait_readable(20);
  }
  return {};
}

/// The board: one UDP socket per channel where the relay sends.
struct Board {
  net::UdpEndpoint hil = open_udp(), vio = open_udp(), gcs = open_udp();
  net::UdpEndpoint& at(Channel c) { return c == Channel::Hil ? hil : (c == Channel::Vio ? vio : gcs); }
};

/// Relay::run on a thread; its log lines collected.
class RelayThread {
 public:
  RelayThread(Board& board, uint16_t tcp_port = 0, uint16_t hil_source_port = 0) {
    adb::RelayConfig c;
    c.tcp_port = tcp_port;
    c.hil_port = board.hil.local_address().port();
    c.vio_port = board.vio.local_address().port();
    c.gcs_port = board.gcs.local_address().port();
    c.hil_source_port = hil_source_port;
    c.gcs_source_port = 0;
    c.hello_timeout_ms = 1000;
    std::string error;
    relay_ = adb::Relay::open(c, [this](const std::string& line) {
      std::lock_guard<std::mutex> lock(mutex_);
      log_ += line + "\n";
    }, &error);
    if (!relay_) throw std::runtime_error(error);
    thread_ = std::thread([this] { relay_->run(stop_); });
  }
  ~RelayThread() {
    stop_.store(true);
    thread_.join();
  }
  uint16_t port() const { return relay_->tcp_port(); }
  adb::RelayStats stats() const { return relay_->stats(); }
  std::string log() {
    std::lock_guard<std::mutex> lock(mutex_);
    return log_;
  }

 private:
  std::unique_ptr<adb::Relay> relay_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::mutex mutex_;
  std::string log_;
};

inline net::SocketAddress loopback(uint16_t port) { return net::SocketAddress::resolve("127.0.0.1", port).value(); }

struct Events {
  std::mutex mutex;
  std::vector<std::string> lines;
  void add(const std::string& l) {
    std::lock_guard<std::mutex> lock(mutex);
    lines.push_back(l);
  }
  bool any(const std::string& needle) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& l : lines)
      if (l.find(needle) != std::string::npos) return true;
    return false;
  }
};

inline std::unique_ptr<net::DatagramTunnel> open_tunnel(uint16_t relay_port, Events* events = nullptr, int link_timeout_ms = 3000) {
  net::DatagramTunnel::Config c;
  c.link_timeout_ms = link_timeout_ms;
  c.reconnect_period_ms = 200;
  if (events) c.on_event = [events](const std::string& l) { events->add(l); };
  auto t = net::DatagramTunnel::open(c, [relay_port]() -> Expected<std::unique_ptr<adb::FramedStream>> {
    auto r = net::connect_to_relay(loopback(relay_port), 2000);
    if (!r.stream) return Error{r.error};
    return std::move(r.stream);
  });
  if (!t) throw std::runtime_error(t.error().message);
  return std::move(t.value());
}

/// A TCP listener on 127.0.0.1 at a port the kernel picks, standing in for the relay: `server` its
/// descriptor, `port` its port. Call it inside ASSERT_NO_FATAL_FAILURE.
inline void listen_on_loopback(int backlog, int& server, uint16_t& port) {
  server = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a = test::loopback_address(0);
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(server, backlog), 0);
  socklen_t len = sizeof a;
  ::getsockname(server, reinterpret_cast<sockaddr*>(&a), &len);
  port = ntohs(a.sin_port);
}

/// A raw TCP connection to the relay, for what a well-behaved host never sends.
class RawClient {
 public:
  explicit RawClient(uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a = test::loopback_address(port);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) throw std::runtime_error("connect failed");
  }
  ~RawClient() { ::close(fd_); }
  void send(const std::vector<uint8_t>& bytes) { ASSERT_EQ(::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bytes.size())); }
  /// Everything until the relay closes the connection (or the timeout).
  std::vector<uint8_t> read_until_closed(std::chrono::milliseconds timeout = 5s, bool* closed = nullptr) {
    std::vector<uint8_t> got;
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      uint8_t buf[4096];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) {
        if (closed) *closed = true;
        return got;
      }
      got.insert(got.end(), buf, buf + n);
    }
    if (closed) *closed = false;
    return got;
  }

 private:
  int fd_ = -1;
};

}  // namespace hitl::relay_test
