// The tunnel's two ends in one process over loopback: DatagramTunnel (the host side) and Relay
// (hitl-adb-relay's loop), with test sockets standing in for the board's ports. Here every datagram
// path and the stream's bounded backlog; the hello, malformed streams, replaced and lost
// connections and the link timeout are in tunnel_relay_connection_test.cpp.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <unistd.h>

#include <vector>

#include "tests/support/process.h"
#include "tests/target/adb-relay/tunnel_relay_fixtures.h"

namespace hitl {
namespace {

using namespace relay_test;

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
