// The one link interface (engine/net/link.h) over loopback: UDP with a fixed peer, udpin learning
// its partner, hearing the peer only, send errors counted; TCP client and server carrying a stream;
// the TCP client's reconnects and what it says.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "base/common/clock.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/net/link.h"
#include "engine/net/open_link.h"
#include "engine/net/tcp_hub_link.h"
#include "engine/net/tcp_links.h"
#include "engine/net/udp_link.h"

namespace hitl::net {
namespace {

std::unique_ptr<UdpLink> udp(uint16_t port, PartnerPolicy policy, std::optional<SocketAddress> peer = std::nullopt,
                             bool hear_peer_only = false, const std::string& bind = "127.0.0.1") {
  UdpLink::Config c;
  c.endpoint.bind_address = bind;
  c.endpoint.bind_port = port;
  c.endpoint.policy = policy;
  c.endpoint.peer = peer;
  c.endpoint.name = "test link";
  c.hear_peer_only = hear_peer_only;
  auto link = UdpLink::open(c);
  EXPECT_TRUE(link.ok()) << link.error().message;
  return std::move(link.value());
}

/// A HEARTBEAT frame from `encoder`'s system (sysid_hint only documents which).
std::vector<uint8_t> heartbeat_frame(uint8_t /*sysid_hint*/, mavlink::FrameEncoder& encoder) {
  mavlink::msg::Heartbeat hb;
  hb.autopilot = 12;
  mavlink::FrameBuffer buf;
  const std::size_t n = encoder.encode(hb, buf);
  return {buf.data(), buf.data() + n};
}

/// Drains `link` for up to timeout_s until `want` frames were parsed.
std::vector<uint8_t> sysids_heard(Link& link, std::size_t want, double timeout_s = 2.0) {
  static const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  std::vector<uint8_t> sysids;
  const double end = monotonic_s() + timeout_s;
  while (sysids.size() < want && monotonic_s() < end) {
    if (!link.wait_readable(50)) continue;
    link.drain(parser, [&](const mavlink::Frame& f) { sysids.push_back(f.sysid); });
  }
  return sysids;
}

TEST(UdpLink, FixedPeerCarriesQueuedFramesAsOneDatagram) {
  auto board = udp(0, PartnerPolicy::LastSender);
  auto sim = udp(0, PartnerPolicy::Fixed, board->local_address());
  mavlink::FrameEncoder e1(1, 1), e2(2, 1);
  const auto f1 = heartbeat_frame(1, e1), f2 = heartbeat_frame(2, e2);
  ASSERT_TRUE(sim->has_room_for(f1.size()));
  sim->queue(f1);
  sim->queue(f2);
  EXPECT_EQ(sim->queued_bytes(), f1.size() + f2.size());
  ASSERT_TRUE(sim->flush().ok());
  EXPECT_EQ(sim->queued_bytes(), 0u);
  EXPECT_EQ(sim->stats().datagrams_out, 1u);  // two frames, one datagram
  EXPECT_EQ(sysids_heard(*board, 2), (std::vector<uint8_t>{1, 2}));
  EXPECT_EQ(board->stats().datagrams_in, 1u);
  // The listener learnt its partner from what it heard, and answers it.
  ASSERT_TRUE(board->peer());
  EXPECT_EQ(*board->peer(), *sim->local_address());
  ASSERT_TRUE(board->send(heartbeat_frame(3, e1)).ok());
  EXPECT_EQ(sysids_heard(*sim, 1).size(), 1u);
}

TEST(UdpLink, HasNoRoomBeyondOneDatagram) {
  auto sim = udp(0, PartnerPolicy::Fixed, SocketAddress::resolve("127.0.0.1", 9).value());
  const std::vector<uint8_t> big(1000, 0xAA);
  EXPECT_TRUE(sim->has_room_for(big.size()));  // an empty batch takes anything
  sim->queue(big);
  EXPECT_TRUE(sim->has_room_for(UdpEndpoint::kMaxDatagram - big.size()));
  EXPECT_FALSE(sim->has_room_for(UdpEndpoint::kMaxDatagram - big.size() + 1));
}

TEST(UdpLink, HearsItsPeerOnlyAndCountsTheRest) {
  auto board = udp(0, PartnerPolicy::LastSender);
  auto sim = udp(0, PartnerPolicy::Fixed, board->local_address(), /*hear_peer_only=*/true);
  auto stranger = udp(0, PartnerPolicy::Fixed, sim->local_address());
  mavlink::FrameEncoder e_sim(250, 1), e_board(1, 1), e_stranger(66, 1);
  ASSERT_TRUE(sim->send(heartbeat_frame(250, e_sim)).ok());
  ASSERT_EQ(sysids_heard(*board, 1).size(), 1u);  // the board learns the simulator
  ASSERT_TRUE(stranger->send(heartbeat_frame(66, e_stranger)).ok());
  ASSERT_TRUE(board->send(heartbeat_frame(1, e_board)).ok());
  const auto heard = sysids_heard(*sim, 1);
  ASSERT_EQ(heard, (std::vector<uint8_t>{1}));
  // The stranger's datagram may be read in the same drain or the next: drain until it was counted.
  const double end = monotonic_s() + 1.0;
  while (sim->stats().ignored_other_address == 0 && monotonic_s() < end) (void)sysids_heard(*sim, 1, 0.05);
  EXPECT_EQ(sim->stats().ignored_other_address, 1u);
}

TEST(UdpLink, CountsRefusedSendsAndSaysTheFirstOnce) {
  // A socket bound to loopback cannot reach another address: the kernel refuses (EINVAL).
  auto sim = udp(0, PartnerPolicy::Fixed, SocketAddress::resolve("192.0.2.1", 14560).value());
  mavlink::FrameEncoder e(250, 1);
  sim->queue(heartbeat_frame(250, e));
  EXPECT_FALSE(sim->flush().ok());
  EXPECT_FALSE(sim->send(heartbeat_frame(250, e)).ok());
  EXPECT_EQ(sim->stats().send_errors, 2u);
  EXPECT_EQ(sim->stats().datagrams_out, 0u);  // never counted as sent
  EXPECT_NE(sim->stats().last_send_errno, 0);
  const auto said = sim->take_send_errors();
  ASSERT_EQ(said.size(), 1u);  // the first refusal per destination, once
  EXPECT_NE(said[0].find("192.0.2.1:14560"), std::string::npos) << said[0];
  EXPECT_TRUE(sim->take_send_errors().empty());
}

TEST(TcpLinks, ServerAndClientCarryAByteStream) {
  auto server = TcpServerLink::listen("127.0.0.1", 0, "--px4-sitl");
  ASSERT_TRUE(server.ok()) << server.error().message;
  auto& s = *server.value();
  EXPECT_FALSE(s.connected());
  EXPECT_FALSE(s.wait_connected(10));  // nobody yet
  TcpClientLink::Config c;
  c.server = *s.local_address();
  c.name = "--connect";
  auto client = TcpClientLink::open(c);
  ASSERT_TRUE(client.ok()) << client.error().message;
  auto& cl = *client.value();
  ASSERT_TRUE(s.wait_connected(1000));
  EXPECT_TRUE(s.peer().has_value());
  EXPECT_EQ(s.stats().connects, 1u);
  // A frame split over two writes is parsed whole: the stream is fed, not taken as datagrams.
  mavlink::FrameEncoder e(1, 1);
  const auto f = heartbeat_frame(1, e);
  ASSERT_TRUE(cl.send(std::span<const uint8_t>(f).first(5)).ok());
  ASSERT_TRUE(cl.send(std::span<const uint8_t>(f).subspan(5)).ok());
  EXPECT_EQ(sysids_heard(s, 1), (std::vector<uint8_t>{1}));
  // Queued frames go out in one write.
  s.queue(heartbeat_frame(2, e));
  s.queue(heartbeat_frame(3, e));
  ASSERT_TRUE(s.flush().ok());
  EXPECT_EQ(s.stats().datagrams_out, 1u);
  EXPECT_EQ(sysids_heard(cl, 2).size(), 2u);
  // The client goes: the server's link is closed for good (PX4 never reconnects).
  client.value().reset();
  const double end = monotonic_s() + 2.0;
  while (!s.closed() && monotonic_s() < end) (void)sysids_heard(s, 1, 0.05);
  EXPECT_TRUE(s.closed());
  EXPECT_FALSE(s.connected());
}

TEST(TcpLinks, ClientWithoutReconnectFailsAtOpenAndStaysClosedAfterALoss) {
  uint16_t port = 0;
  {
    auto server = TcpServerLink::listen("127.0.0.1", 0, "probe");
    ASSERT_TRUE(server.ok());
    port = server.value()->local_address()->port();
  }  // closed: nothing listens there now
  TcpClientLink::Config c;
  c.server = SocketAddress::resolve("127.0.0.1", port).value();
  c.name = "--connect";
  auto client = TcpClientLink::open(c);
  ASSERT_FALSE(client.ok());
  EXPECT_NE(client.error().message.find("--connect: cannot connect to TCP"), std::string::npos) << client.error().message;

  auto server = TcpServerLink::listen("127.0.0.1", 0, "server");
  ASSERT_TRUE(server.ok());
  c.server = *server.value()->local_address();
  auto ok = TcpClientLink::open(c);
  ASSERT_TRUE(ok.ok());
  ASSERT_TRUE(server.value()->wait_connected(1000));
  server.value().reset();  // the server goes away
  auto& cl = *ok.value();
  const double end = monotonic_s() + 2.0;
  while (cl.connected() && monotonic_s() < end) (void)sysids_heard(cl, 1, 0.05);
  EXPECT_FALSE(cl.connected());
  EXPECT_TRUE(cl.closed());
  cl.maintain(monotonic_s() + 100);  // no reconnect asked for: stays down
  EXPECT_FALSE(cl.connected());
  EXPECT_TRUE(cl.take_events().empty());
}

TEST(TcpLinks, ClientReconnectsSayingSoAndSaysAFailedAttemptOnce) {
  auto probe = TcpServerLink::listen("127.0.0.1", 0, "probe");
  ASSERT_TRUE(probe.ok());
  const uint16_t port = probe.value()->local_address()->port();
  probe.value().reset();

  TcpClientLink::Config c;
  c.server = SocketAddress::resolve("127.0.0.1", port).value();
  c.name = "--endpoint tcp:127.0.0.1:" + std::to_string(port);
  c.reconnect_period_s = 2.0;
  auto opened = TcpClientLink::open(c);
  ASSERT_TRUE(opened.ok());  // a reconnecting link opens without a server
  auto& cl = *opened.value();
  EXPECT_FALSE(cl.connected());
  EXPECT_EQ(cl.peer(), c.server);
  cl.maintain(100.0);
  auto events = cl.take_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].severity, Severity::Warning);
  EXPECT_NE(events[0].text.find("; retrying every 2 s"), std::string::npos) << events[0].text;
  cl.maintain(101.0);  // not due yet
  cl.maintain(102.0);  // due, fails again: not said again
  EXPECT_TRUE(cl.take_events().empty());

  auto server = TcpServerLink::listen("127.0.0.1", port, "server");
  ASSERT_TRUE(server.ok()) << server.error().message;
  cl.maintain(104.0);
  ASSERT_TRUE(cl.connected());
  EXPECT_EQ(cl.stats().connects, 1u);
  events = cl.take_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, c.name + ": connected");
  EXPECT_EQ(events[0].severity, Severity::Info);
  ASSERT_TRUE(server.value()->wait_connected(1000));

  server.value().reset();  // the server goes: the link says so and comes back by itself later
  const double end = monotonic_s() + 2.0;
  while (cl.connected() && monotonic_s() < end) (void)sysids_heard(cl, 1, 0.05);
  EXPECT_FALSE(cl.connected());
  EXPECT_FALSE(cl.closed());  // it reconnects
  events = cl.take_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, c.name + ": connection closed; reconnecting every 2 s");
}

/// The first frame `link` hears within timeout_s, with who sent it.
std::optional<std::pair<uint8_t, SocketAddress>> frame_from(Link& link, mavlink::FrameParser& parser, double timeout_s = 2.0) {
  std::optional<std::pair<uint8_t, SocketAddress>> got;
  const double end = monotonic_s() + timeout_s;
  while (!got && monotonic_s() < end) {
    link.maintain(monotonic_s());
    if (!link.wait_readable(20)) continue;
    link.drain_from(parser, [&](const mavlink::Frame& f, const SocketAddress& from) {
      if (!got) got.emplace(f.sysid, from);
    });
  }
  return got;
}

TEST(TcpHubLink, ClientsComeAndGoEachStreamParsedApartAndSendsReachThoseAsked) {
  auto hub = TcpHubLink::listen("127.0.0.1", 0, 2, "--endpoint tcpin:0");
  ASSERT_TRUE(hub.ok()) << hub.error().message;
  auto& h = *hub.value();
  EXPECT_TRUE(h.hub());
  EXPECT_FALSE(h.connected());
  TcpClientLink::Config c;
  c.server = *h.local_address();
  c.name = "gcs";
  auto a = TcpClientLink::open(c);
  auto b = TcpClientLink::open(c);
  ASSERT_TRUE(a.ok() && b.ok());
  const double end = monotonic_s() + 2.0;
  while (h.client_count() < 2 && monotonic_s() < end) h.maintain(monotonic_s());
  ASSERT_EQ(h.client_count(), 2u);
  EXPECT_TRUE(h.connected());
  EXPECT_EQ(h.stats().connects, 2u);
  EXPECT_EQ(h.take_events().size(), 2u);  // "... connected (n connected)"

  // Half a frame from A, then all of B's, then the rest of A's: each stream parsed on its own.
  mavlink::FrameEncoder ea(11, 1), eb(12, 1);
  const auto fa = heartbeat_frame(11, ea), fb = heartbeat_frame(12, eb);
  ASSERT_TRUE(a.value()->send(std::span<const uint8_t>(fa).first(6)).ok());
  static const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  ASSERT_TRUE(b.value()->send(fb).ok());
  auto got_b = frame_from(h, parser);
  ASSERT_TRUE(got_b);
  EXPECT_EQ(got_b->first, 12);
  ASSERT_TRUE(a.value()->send(std::span<const uint8_t>(fa).subspan(6)).ok());
  auto got_a = frame_from(h, parser);
  ASSERT_TRUE(got_a);
  EXPECT_EQ(got_a->first, 11);
  EXPECT_NE(got_a->second, got_b->second);

  // To every client but A (a frame A sent, routed back to the hub): B only.
  mavlink::FrameEncoder board(1, 1);
  ASSERT_TRUE(h.send_to_peers(heartbeat_frame(1, board), got_a->second, {}).ok());
  EXPECT_EQ(sysids_heard(*b.value(), 1), (std::vector<uint8_t>{1}));
  EXPECT_TRUE(sysids_heard(*a.value(), 1, 0.2).empty());
  // To every client.
  ASSERT_TRUE(h.send(heartbeat_frame(1, board)).ok());
  EXPECT_EQ(sysids_heard(*a.value(), 1).size(), 1u);
  EXPECT_EQ(sysids_heard(*b.value(), 1).size(), 1u);

  // A third client is one too many: refused, said once.
  auto third = TcpClientLink::open(c);
  ASSERT_TRUE(third.ok());
  const double later = monotonic_s() + 1.0;
  std::vector<LinkEvent> events;
  while (events.empty() && monotonic_s() < later) {
    h.maintain(monotonic_s());
    events = h.take_events();
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NE(events[0].text.find("refused"), std::string::npos) << events[0].text;
  EXPECT_EQ(h.client_count(), 2u);

  // A goes: B stays served, the hub says so.
  a.value().reset();
  const double gone = monotonic_s() + 2.0;
  while (h.client_count() > 1 && monotonic_s() < gone) (void)frame_from(h, parser, 0.05);
  EXPECT_EQ(h.client_count(), 1u);
  ASSERT_TRUE(h.send(heartbeat_frame(1, board)).ok());
  EXPECT_EQ(sysids_heard(*b.value(), 1).size(), 1u);
}

TEST(OpenLink, EachKindOfTheGrammarOpensItsLink) {
  LinkSettings settings;
  settings.name = "test";
  settings.bind_address = "127.0.0.1";
  // udpin: answers whoever spoke; udp: talks to it from the fixed local port asked for.
  auto listener = udp(0, PartnerPolicy::LastSender);
  const uint16_t port = listener->local_address()->port();
  listener.reset();
  auto udpin = open_link(parse_link_spec("udpin:127.0.0.1:" + std::to_string(port)).value(), settings);
  ASSERT_TRUE(udpin.ok()) << udpin.error().message;
  EXPECT_EQ(udpin.value()->local_address()->port(), port);
  auto out = open_link(parse_link_spec("udp:127.0.0.1:" + std::to_string(port)).value(), settings);
  ASSERT_TRUE(out.ok()) << out.error().message;
  mavlink::FrameEncoder e(7, 1);
  ASSERT_TRUE(out.value()->send(heartbeat_frame(7, e)).ok());
  EXPECT_EQ(sysids_heard(*udpin.value(), 1), (std::vector<uint8_t>{7}));

  // tcpin: one client (PX4 SITL), or a hub with max_clients > 1; tcp: connects to it.
  auto server = open_link(parse_link_spec("tcpin:127.0.0.1:" + std::to_string(port)).value(), settings);
  ASSERT_TRUE(server.ok()) << server.error().message;
  EXPECT_FALSE(server.value()->hub());
  auto client = open_link(parse_link_spec("tcp:127.0.0.1:" + std::to_string(port)).value(), settings);
  ASSERT_TRUE(client.ok()) << client.error().message;
  ASSERT_TRUE(server.value()->wait_connected(1000));
  server.value().reset();
  settings.max_clients = 4;
  auto hub = open_link(parse_link_spec("tcpin:127.0.0.1:" + std::to_string(port)).value(), settings);
  ASSERT_TRUE(hub.ok()) << hub.error().message;
  EXPECT_TRUE(hub.value()->hub());

  // What cannot be opened names the link and the address.
  auto taken = open_link(parse_link_spec("tcpin:127.0.0.1:" + std::to_string(port)).value(), settings);
  ASSERT_FALSE(taken.ok());
  EXPECT_EQ(taken.error().kind, ErrorKind::Unavailable);
  EXPECT_NE(taken.error().message.find("test: cannot listen on TCP 127.0.0.1:" + std::to_string(port)), std::string::npos)
      << taken.error().message;
  settings.host_what = "-i (the board's address)";
  auto unresolvable = open_link(parse_link_spec("udp:no-such-host.invalid:14550").value(), settings);
  ASSERT_FALSE(unresolvable.ok());
  EXPECT_EQ(unresolvable.error().message.rfind("-i (the board's address): cannot resolve host 'no-such-host.invalid'", 0), 0u)
      << unresolvable.error().message;
}

TEST(OpenLink, TheUdpKindsOpenTypedForTheirSocketsFigures) {
  // The bridge's board link: udp: from a fixed local port, hearing its peer only, with its buffers.
  UdpEndpoint::Config bc;
  bc.bind_address = "127.0.0.1";
  auto board = UdpEndpoint::open(bc);
  ASSERT_TRUE(board.ok()) << board.error().message;
  const uint16_t board_port = board->local_address().port();
  LinkSettings settings;
  settings.name = "the board link";
  settings.bind_address = "127.0.0.1";
  settings.hear_peer_only = true;
  settings.receive_buffer_bytes = 64 << 10;
  auto link = open_udp_link(parse_link_spec("udp:127.0.0.1:" + std::to_string(board_port)).value(), settings);
  ASSERT_TRUE(link.ok()) << link.error().message;
  EXPECT_GE(link.value()->buffer_sizes().receive_bytes, 64 << 10);
  EXPECT_EQ(link.value()->peer()->port(), board_port);
  mavlink::FrameEncoder from_board(1, 1), stranger(9, 1);
  const SocketAddress link_address = *link.value()->local_address();
  ASSERT_TRUE(board->send_to(link_address, heartbeat_frame(1, from_board)).ok());
  auto other = udp(0, PartnerPolicy::Fixed, link_address);
  ASSERT_TRUE(other->send(heartbeat_frame(9, stranger)).ok());
  EXPECT_EQ(sysids_heard(*link.value(), 1), (std::vector<uint8_t>{1}));
  EXPECT_EQ(sysids_heard(*link.value(), 1, 0.2), (std::vector<uint8_t>{}));  // the stranger's is dropped, counted
  EXPECT_EQ(link.value()->stats().ignored_other_address, 1u);
  // A stream kind is no UDP link.
  auto tcp = open_udp_link(parse_link_spec("tcp:127.0.0.1:5760").value(), settings);
  ASSERT_FALSE(tcp.ok());
  EXPECT_EQ(tcp.error().kind, ErrorKind::Input);
  EXPECT_NE(tcp.error().message.find("'tcp:127.0.0.1:5760' is not a UDP link"), std::string::npos) << tcp.error().message;
}

TEST(UdpPortInUse, SaysWhetherASocketHoldsThePort) {
  UdpLink::Config c;
  c.endpoint.bind_address = "0.0.0.0";
  auto held = UdpLink::open(c);
  ASSERT_TRUE(held.ok()) << held.error().message;
  const uint16_t port = held.value()->local_address()->port();
  auto in_use = udp_port_in_use(port);
  ASSERT_TRUE(in_use.ok()) << in_use.error().message;
  EXPECT_TRUE(*in_use);
  held.value().reset();
  auto free_now = udp_port_in_use(port);
  ASSERT_TRUE(free_now.ok()) << free_now.error().message;
  EXPECT_FALSE(*free_now);
}

}  // namespace
}  // namespace hitl::net
