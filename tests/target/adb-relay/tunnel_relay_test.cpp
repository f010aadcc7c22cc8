// The tunnel's two ends in one process over loopback: DatagramTunnel (the host side) and Relay
// (hitl-adb-relay's loop), with test sockets standing in for the board's ports. Every datagram
// path, the hello, malformed streams, replaced and lost connections, the link timeout.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/net/datagram_tunnel.h"
#include "engine/net/udp_endpoint.h"
#include "target/adb-relay/relay.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
using adb::Channel;

bool eventually(const std::function<bool()>& done, std::chrono::milliseconds timeout = 10s) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(5ms);
  }
  return done();
}

std::vector<uint8_t> text(const std::string& s) { return {s.begin(), s.end()}; }

net::UdpEndpoint open_udp(uint16_t port = 0) {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.bind_port = port;
  c.policy = net::PartnerPolicy::LastSender;
  return std::move(net::UdpEndpoint::open(c).value());
}

/// Waits for one datagram on `ep`; its text ("" on timeout).
std::string receive_text(net::UdpEndpoint& ep, std::chrono::milliseconds timeout = 5s, net::SocketAddress* from = nullptr) {
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

net::SocketAddress loopback(uint16_t port) { return net::SocketAddress::resolve("127.0.0.1", port).value(); }

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

std::unique_ptr<net::DatagramTunnel> open_tunnel(uint16_t relay_port, Events* events = nullptr, int link_timeout_ms = 3000) {
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

/// A raw TCP connection to the relay, for what a well-behaved host never sends.
class RawClient {
 public:
  explicit RawClient(uint16_t port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
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

TEST(TunnelRelay, DatagramsBothWaysOnEveryChannel) {
  Board board;
  RelayThread relay(board);
  auto tunnel = open_tunnel(relay.port());
  net::UdpEndpoint client = open_udp();
  for (Channel c : adb::kDataChannels) {
    const std::string name = adb::to_string(c);
    ASSERT_TRUE(client.send_to(tunnel->local_endpoint(c), text("to board on " + name)).ok());
    net::SocketAddress relay_source;
    EXPECT_EQ(receive_text(board.at(c), 5s, &relay_source), "to board on " + name);
    // The board answers whoever sent: the relay's socket for this channel.
    ASSERT_TRUE(board.at(c).send(text("reply on " + name)).ok());
    net::SocketAddress from;
    EXPECT_EQ(receive_text(client, 5s, &from), "reply on " + name);
    EXPECT_EQ(from, tunnel->local_endpoint(c)) << "the reply comes from the address the client sent to";
  }
  ASSERT_TRUE(eventually([&] { return tunnel->stats().rtt_ms.has_value(); }));
  const auto s = tunnel->stats();
  EXPECT_TRUE(s.connected);
  EXPECT_EQ(s.connects, 1u);
  EXPECT_LT(*s.rtt_ms, 1000.0);
  // Counters are bumped just after the datagram is handed on: wait for the last ones.
  for (Channel c : adb::kDataChannels) {
    const std::size_t i = adb::index_of(c);
    EXPECT_TRUE(eventually([&] {
      const auto t = tunnel->stats().channels[i];
      const auto r = relay.stats().channels[i];
      return t.to_board == 1 && t.from_board == 1 && r.to_board == 1 && r.from_board == 1;
    })) << adb::to_string(c);
  }
  EXPECT_NE(relay.log().find("host connected from 127.0.0.1:"), std::string::npos) << relay.log();
}

TEST(TunnelRelay, RepliesGoToTheLastLocalSender) {
  Board board;
  RelayThread relay(board);
  auto tunnel = open_tunnel(relay.port());
  net::UdpEndpoint first = open_udp(), second = open_udp();
  ASSERT_TRUE(first.send_to(tunnel->local_endpoint(Channel::Gcs), text("a")).ok());
  EXPECT_EQ(receive_text(board.gcs), "a");
  ASSERT_TRUE(second.send_to(tunnel->local_endpoint(Channel::Gcs), text("b")).ok());
  EXPECT_EQ(receive_text(board.gcs), "b");
  ASSERT_TRUE(board.gcs.send(text("answer")).ok());
  EXPECT_EQ(receive_text(second), "answer");
  EXPECT_EQ(receive_text(first, 300ms), "");
}

TEST(TunnelRelay, BoardDatagramsBeforeAnyClientAreCountedNotSent) {
  Board board;
  const uint16_t hil_source = test::free_udp_port();
  RelayThread relay(board, 0, hil_source);
  auto tunnel = open_tunnel(relay.port());
  // The relay forwards once it has the host's hello (before that it counts the datagram as dropped).
  ASSERT_TRUE(eventually([&] { return relay.stats().host_connected; }));
  ASSERT_TRUE(board.hil.send_to(loopback(hil_source), text("actuators")).ok());
  EXPECT_TRUE(eventually([&] { return tunnel->stats().channels[adb::index_of(Channel::Hil)].dropped_no_client == 1; }));
  EXPECT_EQ(tunnel->stats().channels[adb::index_of(Channel::Hil)].from_board, 0u);
}

TEST(TunnelRelay, OversizeDatagramIsDroppedAndCounted) {
  Board board;
  RelayThread relay(board);
  auto tunnel = open_tunnel(relay.port());
  net::UdpEndpoint client = open_udp();
  const std::vector<uint8_t> big(adb::kMaxDatagram_bytes + 1, 0x55);
  ASSERT_TRUE(client.send_to(tunnel->local_endpoint(Channel::Hil), big).ok());
  EXPECT_TRUE(eventually([&] { return tunnel->stats().channels[adb::index_of(Channel::Hil)].dropped_too_large == 1; }));
  const std::vector<uint8_t> largest(adb::kMaxDatagram_bytes, 0x66);
  ASSERT_TRUE(client.send_to(tunnel->local_endpoint(Channel::Hil), largest).ok());
  EXPECT_EQ(receive_text(board.hil).size(), adb::kMaxDatagram_bytes);
  EXPECT_TRUE(tunnel->stats().connected);
}

TEST(TunnelRelay, MalformedStreamsAreDroppedAndTheRelayServesOn) {
  Board board;
  RelayThread relay(board);
  {
    RawClient http(relay.port());
    http.send(text("GET / HTTP/1.1\r\nHost: x\r\n\r\n"));
    bool closed = false;
    http.read_until_closed(5s, &closed);
    EXPECT_TRUE(closed);
  }
  {
    RawClient bad_frame(relay.port());
    std::vector<uint8_t> bytes;
    adb::append_hello(bytes);
    bytes.insert(bytes.end(), {0, 2, 9, 1, 2});  // channel 9
    bad_frame.send(bytes);
    bool closed = false;
    const auto got = bad_frame.read_until_closed(5s, &closed);
    EXPECT_TRUE(closed);
    EXPECT_GE(got.size(), adb::kHelloSize_bytes);  // the relay's hello came first
  }
  {
    RawClient silent(relay.port());  // connects, never says hello: dropped after hello_timeout_ms
    bool closed = false;
    silent.read_until_closed(5s, &closed);
    EXPECT_TRUE(closed);
  }
  EXPECT_TRUE(eventually([&] { return relay.stats().malformed == 3; })) << relay.log();
  const std::string log = relay.log();
  EXPECT_NE(log.find("not a hitl adb tunnel: the stream starts with 'GET / HT'"), std::string::npos) << log;
  EXPECT_NE(log.find("malformed frame 1: unknown channel 9"), std::string::npos) << log;
  EXPECT_NE(log.find("no hello within 1000 ms"), std::string::npos) << log;
  // And a real host is served afterwards.
  auto tunnel = open_tunnel(relay.port());
  net::UdpEndpoint client = open_udp();
  ASSERT_TRUE(client.send_to(tunnel->local_endpoint(Channel::Vio), text("odometry")).ok());
  EXPECT_EQ(receive_text(board.vio), "odometry");
}

TEST(TunnelRelay, VersionMismatchIsAClearErrorAtBothEnds) {
  Board board;
  RelayThread relay(board);
  RawClient future_host(relay.port());
  std::vector<uint8_t> hello;
  adb::append_hello(hello, adb::Hello{99, 8192});
  future_host.send(hello);
  bool closed = false;
  const auto got = future_host.read_until_closed(5s, &closed);
  EXPECT_TRUE(closed);
  ASSERT_GE(got.size(), adb::kHelloSize_bytes);
  EXPECT_EQ(adb::parse_hello(got.data(), got.size()).hello->version, adb::kProtocolVersion);  // says what it speaks
  EXPECT_TRUE(eventually([&] { return relay.stats().version_mismatches == 1; }));
  EXPECT_NE(relay.log().find("the host speaks tunnel protocol version 99, this relay speaks version 1"), std::string::npos)
      << relay.log();

  // The host side against a relay of another version.
  const int server = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(server, 1), 0);
  socklen_t len = sizeof a;
  ::getsockname(server, reinterpret_cast<sockaddr*>(&a), &len);
  std::thread old_relay([server] {
    const int fd = ::accept(server, nullptr, nullptr);
    std::vector<uint8_t> h;
    adb::append_hello(h, adb::Hello{2, 8192});
    (void)!::send(fd, h.data(), h.size(), MSG_NOSIGNAL);
    std::this_thread::sleep_for(500ms);
    ::close(fd);
  });
  const auto r = net::connect_to_relay(loopback(ntohs(a.sin_port)), 3000);
  old_relay.join();
  ::close(server);
  EXPECT_FALSE(r.stream);
  EXPECT_FALSE(r.relay_absent);
  EXPECT_NE(r.error.find("hitl-adb-relay on the board speaks tunnel protocol version 2, this hitl speaks version 1"), std::string::npos)
      << r.error;
}

TEST(TunnelRelay, NothingListeningIsReportedAsAbsent) {
  const uint16_t closed_port = test::free_udp_port();  // a free number; nothing listens on it over TCP
  const auto refused = net::connect_to_relay(loopback(closed_port), 2000);
  EXPECT_FALSE(refused.stream);
  EXPECT_TRUE(refused.relay_absent) << refused.error;
  // What adb does when nothing listens on the board: it accepts, then closes.
  const int server = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(server, 1), 0);
  socklen_t len = sizeof a;
  ::getsockname(server, reinterpret_cast<sockaddr*>(&a), &len);
  std::thread closer([server] { ::close(::accept(server, nullptr, nullptr)); });
  const auto closed = net::connect_to_relay(loopback(ntohs(a.sin_port)), 2000);
  closer.join();
  ::close(server);
  EXPECT_FALSE(closed.stream);
  EXPECT_TRUE(closed.relay_absent) << closed.error;
  EXPECT_NE(closed.error.find("closed at once (no relay listening on the board)"), std::string::npos) << closed.error;
}

TEST(TunnelRelay, ANewHostReplacesTheCurrentOne) {
  Board board;
  RelayThread relay(board);
  Events events;
  auto tunnel = open_tunnel(relay.port(), &events);
  {
    RawClient newcomer(relay.port());
    std::vector<uint8_t> hello;
    adb::append_hello(hello);
    newcomer.send(hello);
    // The tunnel loses its stream to the newcomer, then takes it back (replacing the newcomer).
    EXPECT_TRUE(eventually([&] { return tunnel->stats().link_losses >= 1; }));
    bool closed = false;
    newcomer.read_until_closed(10s, &closed);
    EXPECT_TRUE(closed);
  }
  EXPECT_TRUE(eventually([&] { return tunnel->stats().connected && tunnel->stats().connects >= 2; }));
  EXPECT_GE(relay.stats().replaced, 2u);
  EXPECT_NE(relay.log().find("a new host connection from 127.0.0.1:"), std::string::npos) << relay.log();
  EXPECT_TRUE(events.any("link to the relay lost"));
  EXPECT_TRUE(events.any("link to the relay restored"));
  net::UdpEndpoint client = open_udp();
  ASSERT_TRUE(client.send_to(tunnel->local_endpoint(Channel::Hil), text("after")).ok());
  EXPECT_EQ(receive_text(board.hil), "after");
}

TEST(TunnelRelay, RelayRestartIsSurvivedWithTheSameLocalEndpoints) {
  Board board;
  Events events;
  auto first = std::make_unique<RelayThread>(board);
  const uint16_t port = first->port();
  auto tunnel = open_tunnel(port, &events);
  const auto hil_endpoint = tunnel->local_endpoint(Channel::Hil);
  net::UdpEndpoint client = open_udp();
  ASSERT_TRUE(client.send_to(hil_endpoint, text("one")).ok());
  EXPECT_EQ(receive_text(board.hil), "one");
  first.reset();  // the relay goes away (board rebooted, relay killed)
  ASSERT_TRUE(eventually([&] { return !tunnel->stats().connected; }));
  ASSERT_TRUE(client.send_to(hil_endpoint, text("lost")).ok());
  EXPECT_TRUE(eventually([&] { return tunnel->stats().channels[adb::index_of(Channel::Hil)].dropped_no_link >= 1; }));
  RelayThread second(board, port);
  ASSERT_TRUE(eventually([&] { return tunnel->stats().connected; }, 15s)) << tunnel->stats().last_error;
  EXPECT_EQ(tunnel->local_endpoint(Channel::Hil), hil_endpoint);
  ASSERT_TRUE(client.send_to(hil_endpoint, text("two")).ok());
  EXPECT_EQ(receive_text(board.hil), "two");
  EXPECT_EQ(tunnel->stats().link_losses, 1u);
  EXPECT_TRUE(events.any("still no link"));
}

TEST(TunnelRelay, ASilentRelayIsNoticedWithinTheLinkTimeout) {
  // Hello, then nothing: a relay whose board froze, or a stalled adb.
  const int server = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(server, 4), 0);
  socklen_t len = sizeof a;
  ::getsockname(server, reinterpret_cast<sockaddr*>(&a), &len);
  std::atomic<bool> stop{false};
  std::vector<int> accepted;
  std::thread frozen([&] {
    while (!stop.load()) {
      pollfd p{server, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      const int fd = ::accept(server, nullptr, nullptr);
      std::vector<uint8_t> h;
      adb::append_hello(h);
      (void)!::send(fd, h.data(), h.size(), MSG_NOSIGNAL);
      accepted.push_back(fd);
    }
  });
  Events events;
  auto tunnel = open_tunnel(ntohs(a.sin_port), &events, 600);
  EXPECT_TRUE(eventually([&] { return tunnel->stats().link_losses >= 1; }));
  EXPECT_TRUE(events.any("no answer from the relay for 600 ms")) << tunnel->stats().last_error;
  tunnel.reset();
  stop.store(true);
  frozen.join();
  for (int fd : accepted) ::close(fd);
  ::close(server);
}

TEST(FramedStream, BacklogIsBounded) {
  int fds[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
  adb::FramedStream stream(fds[0], 4096);
  const std::vector<uint8_t> d(1000, 1);
  int queued = 0;
  while (stream.queue(Channel::Hil, d.data(), d.size()) == adb::FramedStream::Queued::Yes) ++queued;
  EXPECT_EQ(queued, 4);  // 4 x 1003 bytes fit in 4096
  EXPECT_EQ(stream.queue(Channel::Hil, d.data(), d.size()), adb::FramedStream::Queued::BacklogFull);
  const std::vector<uint8_t> big(adb::kMaxDatagram_bytes + 1, 1);
  EXPECT_EQ(stream.queue(Channel::Hil, big.data(), big.size()), adb::FramedStream::Queued::TooLarge);
  EXPECT_TRUE(stream.flush().empty());
  EXPECT_EQ(stream.backlog(), 0u);
  EXPECT_EQ(stream.queue(Channel::Hil, d.data(), d.size()), adb::FramedStream::Queued::Yes);
  ::close(fds[1]);
}

}  // namespace
}  // namespace hitl
