// The tunnel's connection between DatagramTunnel (the host side) and Relay (hitl-adb-relay's loop)
// over loopback: malformed streams and a version mismatch in the hello, nothing listening, a new
// host replacing the current one, a relay restart, a silent relay noticed within the link timeout.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <thread>
#include <vector>

#include "tests/support/process.h"
#include "tests/target/adb-relay/tunnel_relay_fixtures.h"

namespace hitl {
namespace {

using namespace relay_test;

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
  int server = -1;
  uint16_t port = 0;
  ASSERT_NO_FATAL_FAILURE(listen_on_loopback(1, server, port));
  std::thread old_relay([server] {
    const int fd = ::accept(server, nullptr, nullptr);
    std::vector<uint8_t> h;
    adb::append_hello(h, adb::Hello{2, 8192});
    (void)!::send(fd, h.data(), h.size(), MSG_NOSIGNAL);
    std::this_thread::sleep_for(500ms);
    ::close(fd);
  });
  const auto r = net::connect_to_relay(loopback(port), 3000);
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
  int server = -1;
  uint16_t port = 0;
  ASSERT_NO_FATAL_FAILURE(listen_on_loopback(1, server, port));
  std::thread closer([server] { ::close(::accept(server, nullptr, nullptr)); });
  const auto closed = net::connect_to_relay(loopback(port), 2000);
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
  int server = -1;
  uint16_t port = 0;
  ASSERT_NO_FATAL_FAILURE(listen_on_loopback(4, server, port));
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
  auto tunnel = open_tunnel(port, &events, 600);
  EXPECT_TRUE(eventually([&] { return tunnel->stats().link_losses >= 1; }));
  EXPECT_TRUE(events.any("no answer from the relay for 600 ms")) << tunnel->stats().last_error;
  tunnel.reset();
  stop.store(true);
  frozen.join();
  for (int fd : accepted) ::close(fd);
  ::close(server);
}

}  // namespace
}  // namespace hitl
