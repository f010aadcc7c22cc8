// The client port's bounds (issue 19): at most max_clients learned, further senders refused and
// counted; broadcast() only queues; pump() sends at most max_datagrams_out, the board's and the
// owner's frames before client-to-client ones; a full queue drops and counts.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "engine/net/client_port.h"

namespace hitl::net {
namespace {

using namespace std::chrono_literals;

UdpEndpoint peer(uint16_t to_port) {
  UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.peer = SocketAddress::resolve("127.0.0.1", to_port).value();
  c.policy = PartnerPolicy::Fixed;
  return std::move(UdpEndpoint::open(c).value());
}

/// A client port on an ephemeral port: with port 0 it opens its socket only for a fixed peer, so it
/// gets one (a sink nobody reads, as a --gcs would be).
struct Fixture {
  explicit Fixture(const ClientPortLimits& limits)
      : sink(std::move(UdpEndpoint::open(UdpEndpoint::Config{"127.0.0.1", 0, std::nullopt, PartnerPolicy::Fixed, "sink"}).value())),
        port(std::move(ClientPort::open("127.0.0.1", 0, {sink.local_address()}, limits).value())) {}
  UdpEndpoint sink;
  ClientPort port;
};

std::size_t drain(UdpEndpoint& e) {
  std::size_t n = 0;
  while (e.wait_readable(50))
    while (e.receive()) ++n;
  return n;
}

TEST(ClientPort, RefusesSendersBeyondTheClientLimitAndCountsThem) {
  ClientPortLimits limits;
  limits.max_clients = 3;  // the fixed peer (a --gcs) is one of them
  Fixture f(limits);
  const uint16_t port = f.port.local_address()->port();
  std::vector<UdpEndpoint> senders;
  for (int i = 0; i < 5; ++i) senders.push_back(peer(port));
  const uint8_t hello[] = {1, 2, 3};
  for (auto& s : senders) ASSERT_TRUE(s.send(hello));
  std::this_thread::sleep_for(50ms);
  std::size_t delivered = 0;
  const std::size_t read = f.port.receive_some(100, [&](const Datagram&) { ++delivered; });
  EXPECT_EQ(read, 5u);
  EXPECT_EQ(delivered, 2u);
  EXPECT_EQ(f.port.client_count(), 3u);
  EXPECT_EQ(f.port.stats().refused_datagrams, 3u);
  // A known client is still heard.
  ASSERT_TRUE(senders[0].send(hello));
  std::this_thread::sleep_for(50ms);
  delivered = 0;
  f.port.receive_some(100, [&](const Datagram&) { ++delivered; });
  EXPECT_EQ(delivered, 1u);
}

TEST(ClientPort, ReadsNoMoreThanItIsGiven) {
  Fixture f({});
  auto s = peer(f.port.local_address()->port());
  const uint8_t hello[] = {1};
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(s.send(hello));
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(f.port.receive_some(4, [](const Datagram&) {}), 4u);
  EXPECT_EQ(f.port.receive_some(100, [](const Datagram&) {}), 6u);
}

TEST(ClientPort, PumpSendsAtMostItsBudgetOwnFramesFirst) {
  ClientPortLimits limits;
  limits.max_datagrams_out = 4;
  limits.max_queued_frames = 2;
  Fixture f(limits);
  const uint16_t port = f.port.local_address()->port();
  std::vector<UdpEndpoint> clients;
  for (int i = 0; i < 3; ++i) clients.push_back(peer(port));
  const uint8_t hello[] = {0};
  for (auto& c : clients) ASSERT_TRUE(c.send(hello));
  std::this_thread::sleep_for(50ms);
  std::optional<SocketAddress> first;
  f.port.receive_some(100, [&](const Datagram& d) {
    if (!first) first = d.from;
  });
  ASSERT_EQ(f.port.client_count(), 4u);  // the fixed sink and three clients
  const uint8_t forwarded[] = {9};
  const uint8_t own[] = {7};
  f.port.broadcast(forwarded, first);  // to the sink and the two other clients: 3 datagrams
  f.port.broadcast(own);               // to all four
  f.port.broadcast(own);
  f.port.broadcast(own);               // the own queue holds two: dropped
  EXPECT_EQ(f.port.stats().dropped_frames, 1u);
  f.port.pump();
  EXPECT_EQ(f.port.stats().datagrams_out, 4u);  // the first own frame, to all four
  std::size_t got = 0;
  for (auto& c : clients) got += drain(c);
  EXPECT_EQ(got, 3u);
  f.port.pump();
  f.port.pump();
  EXPECT_EQ(f.port.stats().datagrams_out, 4u + 4u + 3u);
  EXPECT_EQ(f.port.queued_frames(), 0u);
  got = 0;
  for (auto& c : clients) got += drain(c);
  EXPECT_EQ(got, 3u + 2u);  // the second own frame to each, the forwarded one to the two others
}

}  // namespace
}  // namespace hitl::net

namespace hitl::net {
namespace {

/// A MAVLink 2 frame's bytes with message id `id` and `index` as its first payload byte (the
/// client port reads only the id; the checksum is not its business).
std::vector<uint8_t> frame_bytes(uint32_t id, uint8_t index) {
  std::vector<uint8_t> f(20, 0);
  f[0] = 0xFD;
  f[1] = 8;
  f[7] = static_cast<uint8_t>(id);
  f[8] = static_cast<uint8_t>(id >> 8);
  f[9] = static_cast<uint8_t>(id >> 16);
  f[10] = index;
  return f;
}

// Issue 34: a fresh queue (max_queue_s) full drops its OLDEST frame, counted per client it did
// not reach and by message id; the newest are sent, in order.
TEST(ClientPort, AFreshQueueDropsTheOldestAndCountsThemByMessage) {
  ClientPortLimits limits;
  limits.max_datagrams_out = 4;
  limits.min_queued_frames = 4;
  limits.max_queue_s = 1e-9;  // the queue at its floor: 4 frames
  Fixture f(limits);
  for (uint8_t i = 0; i < 10; ++i) f.port.broadcast(frame_bytes(i < 5 ? 30 : 105, i));
  EXPECT_EQ(f.port.queued_frames(), 4u);
  f.port.pump();
  std::vector<uint8_t> got;
  while (f.sink.wait_readable(50))
    while (auto d = f.sink.receive()) got.push_back(d->bytes[10]);
  EXPECT_EQ(got, (std::vector<uint8_t>{6, 7, 8, 9}));
  const auto& s = f.port.stats();
  EXPECT_EQ(s.dropped_frames, 6u);
  EXPECT_EQ(s.dropped_deliveries, 6u);  // one client (the fixed peer)
  EXPECT_EQ(s.dropped_by_msgid.at(30), 5u);
  EXPECT_EQ(s.dropped_by_msgid.at(105), 1u);
}

// The session's queue (max_queue_s 0) keeps what it holds and refuses the newest, as before.
TEST(ClientPort, ACountBoundQueueRefusesTheNewest) {
  ClientPortLimits limits;
  limits.max_datagrams_out = 4;
  limits.max_queued_frames = 4;
  Fixture f(limits);
  for (uint8_t i = 0; i < 10; ++i) f.port.broadcast(frame_bytes(30, i));
  f.port.pump();
  std::vector<uint8_t> got;
  while (f.sink.wait_readable(50))
    while (auto d = f.sink.receive()) got.push_back(d->bytes[10]);
  EXPECT_EQ(got, (std::vector<uint8_t>{0, 1, 2, 3}));
  EXPECT_EQ(f.port.stats().dropped_frames, 6u);
}

}  // namespace
}  // namespace hitl::net
