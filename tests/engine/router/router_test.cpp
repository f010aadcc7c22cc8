// The router both hitl sim and hitl bridge route with: mavlink-router's rules, dedup, hub links.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_check.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/router/router.h"

namespace hitl::router {
namespace {

namespace msg = mavlink::msg;

struct Sink {
  std::vector<std::vector<uint8_t>> frames;
  std::vector<std::optional<net::SocketAddress>> excepts;
  std::vector<std::vector<net::SocketAddress>> onlys;
  Sender sender() {
    return [this](std::span<const uint8_t> b, const Delivery& to) {
      frames.emplace_back(b.begin(), b.end());
      excepts.push_back(to.except);
      onlys.push_back(to.only);
    };
  }
};

class RouterTest : public ::testing::Test {
 protected:
  template <class M>
  mavlink::Frame frame(const M& m, uint8_t sysid, uint8_t compid, uint8_t seq = 0) {
    mavlink::FrameEncoder enc(sysid, compid);
    for (uint8_t i = 0; i < seq; ++i) {  // advance the sender's sequence
      mavlink::FrameBuffer skip;
      enc.encode(m, skip);
    }
    mavlink::FrameBuffer buf;
    const auto n = enc.encode(m, buf);
    std::optional<mavlink::Frame> out;
    parser_.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) { out = f; });
    return *out;
  }
  msg::CommandLong command_to(uint8_t system, uint8_t component) {
    msg::CommandLong c;
    c.target_system = system;
    c.target_component = component;
    c.command = 400;
    return c;
  }
  mavlink::MessageSet set_ = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser_{set_};
};

// Issue 19: an id hitl does not know has no checkable checksum. As mavlink-router does, it is
// forwarded only when its framing is whole; junk that looks like one is never forwarded.
TEST_F(RouterTest, UnknownIdIsForwardedOnlyWhenItsFramingIsWhole) {
  Router r;
  Sink a, b;
  const auto la = r.add_link("a", a.sender());
  r.add_link("b", b.sender());
  mavlink::FrameEncoder enc(1, 1);
  mavlink::FrameBuffer buf;
  const std::vector<uint8_t> payload = {1, 2, 3, 4, 5};
  const std::size_t n = enc.encode_raw(60001, 0, payload, 5, buf);
  const std::vector<uint8_t> whole(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  auto route_datagram = [&](const std::vector<uint8_t>& d) {
    parser_.parse_datagram(d, [&](const mavlink::Frame& f) { r.route(f, la, 0.0); });
  };
  route_datagram(whole);  // alone in its datagram: whole
  ASSERT_EQ(b.frames.size(), 1u);
  EXPECT_EQ(b.frames[0], whole);
  auto followed = whole;
  followed.insert(followed.end(), {0x11, 0x22, 0x33});  // junk after it: not whole
  route_datagram(followed);
  auto stray = std::vector<uint8_t>{0xFD, 40, 0, 0, 0, 1, 1, 0x61, 0xEA, 0};  // a stray header
  stray.resize(100, 0x5A);
  route_datagram(stray);
  EXPECT_EQ(b.frames.size(), 1u);
}

TEST_F(RouterTest, BroadcastGoesEverywhereButBack) {
  Router r;
  Sink a, b, c;
  const auto la = r.add_link("a", a.sender());
  r.add_link("b", b.sender());
  r.add_link("c", c.sender());
  EXPECT_EQ(r.route(frame(msg::Heartbeat{}, 1, 1), la, 0.0), 2u);
  EXPECT_TRUE(a.frames.empty());
  EXPECT_EQ(b.frames.size(), 1u);
  EXPECT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(r.counters(la).frames_in, 1u);
}

TEST_F(RouterTest, TargetedFramesGoOnlyWhereTheTargetWasSeen) {
  Router r;
  Sink board, gcs, other;
  const auto lb = r.add_link("board", board.sender());
  const auto lg = r.add_link("gcs", gcs.sender());
  const auto lo = r.add_link("other", other.sender());
  // Nobody has shown system 1 yet: a command for it goes everywhere (a silent vehicle still gets it).
  EXPECT_EQ(r.route(frame(command_to(1, 1), 255, 190), lg, 0.0), 2u);
  r.route(frame(msg::Heartbeat{}, 1, 1), lb, 0.1);  // the board speaks
  r.route(frame(msg::Heartbeat{}, 2, 1), lo, 0.1);  // another vehicle elsewhere
  board.frames.clear();
  other.frames.clear();
  EXPECT_EQ(r.route(frame(command_to(1, 1), 255, 190, 1), lg, 0.2), 1u);
  EXPECT_EQ(board.frames.size(), 1u);
  EXPECT_TRUE(other.frames.empty());
  // A component the board has not shown: not sent there.
  EXPECT_EQ(r.route(frame(command_to(1, 77), 255, 190, 2), lg, 0.3), 0u);
  // Component 0 means any component of the system.
  EXPECT_EQ(r.route(frame(command_to(2, 0), 255, 190, 3), lg, 0.4), 1u);
  EXPECT_EQ(other.frames.size(), 1u);
}

TEST_F(RouterTest, ManualControlNamesItsTargetInTarget) {
  msg::ManualControl m;
  m.target = 7;
  EXPECT_EQ(target_of(frame(m, 255, 190)).first, 7);
  EXPECT_EQ(target_of(frame(msg::Heartbeat{}, 1, 1)), std::make_pair(uint8_t{0}, uint8_t{0}));
}

TEST_F(RouterTest, HubLinksReachTheirOtherPeersButNotTheSender) {
  Router r;
  Sink board, clients;
  r.add_link("board", board.sender());
  const auto lc = r.add_link("clients", clients.sender(), /*hub=*/true);
  auto peer = net::SocketAddress::parse("127.0.0.1:40000", "peer");
  ASSERT_TRUE(peer.ok());
  r.route(frame(msg::Heartbeat{}, 255, 190), lc, 0.0, *peer);
  ASSERT_EQ(board.frames.size(), 1u);
  ASSERT_EQ(clients.frames.size(), 1u);
  EXPECT_EQ(clients.excepts[0], *peer);
}

// Issue 27: a command from client A targeted at client B (both on the shared client port) reached
// every client but A; the hub now remembers which address showed which sysid/compid.
TEST_F(RouterTest, ATargetedFrameOnTheHubGoesOnlyToThePeerThatShowedTheTarget) {
  Router r;
  Sink board, clients;
  r.add_link("board", board.sender());
  const auto lc = r.add_link("clients", clients.sender(), /*hub=*/true);
  const auto a = net::SocketAddress::parse("127.0.0.1:40001", "a").value();
  const auto b = net::SocketAddress::parse("127.0.0.1:40002", "b").value();
  const auto c = net::SocketAddress::parse("127.0.0.1:40003", "c").value();
  r.route(frame(msg::Heartbeat{}, 200, 1), lc, 0.0, a);
  r.route(frame(msg::Heartbeat{}, 201, 1), lc, 0.0, b);
  r.route(frame(msg::Heartbeat{}, 202, 1), lc, 0.0, c);
  EXPECT_EQ(r.peer_systems(lc), 3u);
  const std::size_t before = clients.frames.size();
  r.route(frame(command_to(201, 1), 200, 1), lc, 0.0, a);
  ASSERT_EQ(clients.frames.size(), before + 1);
  EXPECT_EQ(clients.onlys.back(), std::vector<net::SocketAddress>{b});
  EXPECT_EQ(board.frames.size(), 3u);  // the board has not shown 201: not sent there
  // Component 0: any component of that system; a broadcast still reaches every other peer.
  r.route(frame(command_to(201, 0), 200, 1), lc, 0.0, a);
  EXPECT_EQ(clients.onlys.back(), std::vector<net::SocketAddress>{b});
  r.route(frame(msg::Heartbeat{}, 200, 1), lc, 0.0, a);
  EXPECT_TRUE(clients.onlys.back().empty());
  // From the board to a client's system: that client only.
  const auto lb = LinkId{0};
  r.route(frame(command_to(202, 1), 1, 1), lb, 0.0);
  EXPECT_EQ(clients.onlys.back(), std::vector<net::SocketAddress>{c});
  EXPECT_FALSE(clients.excepts.back().has_value());
}

TEST_F(RouterTest, AStandardIdWithoutATypeIsTargetedByTheXmlsOffsets) {
  // SET_MODE (#11) is not typed in hitl; its target_system sits at payload offset 4.
  mavlink::FrameEncoder enc(255, 190);
  mavlink::FrameBuffer buf;
  const std::vector<uint8_t> payload = {1, 0, 0, 0, 42, 1};
  const std::size_t n = enc.encode_raw(11, mavlink::find_standard_check(11)->crc_extra, payload, 6, buf);
  std::optional<mavlink::Frame> f;
  parser_.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& got) { f = got; });
  ASSERT_TRUE(f);
  EXPECT_EQ(target_of(*f), std::make_pair(uint8_t{42}, uint8_t{0}));
}

TEST_F(RouterTest, AHubRemembersABoundedNumberOfPeerSystemsTheStalestGoFirst) {
  Router r;
  Sink board, clients;
  r.add_link("board", board.sender());
  const auto lc = r.add_link("clients", clients.sender(), /*hub=*/true);
  for (int i = 0; i < 600; ++i) {
    const auto peer = net::SocketAddress::parse("127.0.0.1:" + std::to_string(20000 + i), "p").value();
    r.route(frame(msg::Heartbeat{}, 9, 9), lc, 0.0, peer);
  }
  EXPECT_EQ(r.peer_systems(lc), Router::kMaxSystemsPerLink);
  EXPECT_EQ(r.counters(lc).peers_forgotten, 600u - Router::kMaxSystemsPerLink);
  r.route(frame(command_to(9, 9), 1, 1), 0, 0.0);
  ASSERT_EQ(clients.onlys.back().size(), Router::kMaxSystemsPerLink);
  EXPECT_EQ(clients.onlys.back().back().port(), 20599);  // the newest kept
}

TEST_F(RouterTest, ALinkLearnsABoundedNumberOfSystems) {
  // Issue 19: a client inventing sysid/compid pairs must not make every lookup grow.
  Router r;
  Sink a, b;
  const auto la = r.add_link("a", a.sender());
  r.add_link("b", b.sender());
  for (int i = 0; i < 600; ++i) r.route(frame(msg::Heartbeat{}, static_cast<uint8_t>(1 + i % 250), static_cast<uint8_t>(i / 250 + 1)), la, 0.0);
  EXPECT_EQ(r.systems(la).size(), Router::kMaxSystemsPerLink);
  EXPECT_EQ(r.counters(la).systems_not_learned, 600u - Router::kMaxSystemsPerLink);
  EXPECT_EQ(b.frames.size(), 600u);  // still routed
}

TEST_F(RouterTest, DuplicatesWithinTheWindowAreDroppedOnceAndCounted) {
  Router r(0.5);
  Sink a, b, c;
  const auto la = r.add_link("wifi", a.sender());
  const auto lb = r.add_link("usb", b.sender());
  r.add_link("gcs", c.sender());
  const auto f = frame(msg::Heartbeat{}, 1, 1, 5);
  EXPECT_EQ(r.route(f, la, 0.0), 2u);
  EXPECT_EQ(r.route(f, lb, 0.1), 0u);  // the same frame on the second path
  EXPECT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(r.duplicates(), 1u);
  EXPECT_EQ(r.counters(lb).duplicates_in, 1u);
  EXPECT_EQ(r.route(frame(msg::Heartbeat{}, 1, 1, 6), lb, 0.2), 2u);  // a new seq is a new frame
  EXPECT_EQ(r.route(f, lb, 1.0), 2u);  // outside the window: passes again
}

}  // namespace
}  // namespace hitl::router
