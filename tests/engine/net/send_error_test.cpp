// A refused send is counted as an error, never as sent, and said once per destination with the
// errno and the likely fix. Without a real network: a socket bound to 127.0.0.1 cannot reach
// another address (the kernel says EINVAL at once), the same on every Linux machine.
#include <gtest/gtest.h>

#include <cerrno>

#include "engine/net/send_error.h"
#include "engine/net/udp_endpoint.h"

namespace hitl::net {
namespace {

SocketAddress address(const std::string& host, uint16_t port) { return SocketAddress::resolve(host, port).value(); }

TEST(SendError, NoRouteSaysTheUsbEthernetAddressAsDoctorDoes) {
  const auto text = describe_send_error(ENETUNREACH, address("0.0.0.0", 0), address("192.168.101.2", 14560));
  EXPECT_NE(text.find("cannot send to 192.168.101.2:14560"), std::string::npos) << text;
  EXPECT_NE(text.find("ENETUNREACH"), std::string::npos) << text;
  EXPECT_NE(text.find("sudo ip addr add 192.168.101.100/24 dev usb0"), std::string::npos) << text;
  EXPECT_NE(text.find("hitl doctor -i 192.168.101.2"), std::string::npos) << text;
}

TEST(SendError, LoopbackBindCannotReachABoard) {
  const auto text = describe_send_error(EINVAL, address("127.0.0.1", 5000), address("192.0.2.1", 14560));
  EXPECT_NE(text.find("EINVAL"), std::string::npos) << text;
  EXPECT_NE(text.find("bound to 127.0.0.1 (--bind)"), std::string::npos) << text;
  EXPECT_TRUE(send_error_hint(EINVAL, address("0.0.0.0", 0), address("192.0.2.1", 1)).empty());
}

TEST(SendError, EndpointCountsRefusalsAndSaysEachDestinationOnce) {
  UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.peer = address("192.0.2.1", 14560);
  c.policy = PartnerPolicy::Fixed;
  c.name = "HIL link";
  auto ep = UdpEndpoint::open(c);
  ASSERT_TRUE(ep) << ep.error().message;
  const uint8_t byte = 0;
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(ep->send({&byte, 1}));
  EXPECT_FALSE(ep->send_to(address("192.0.2.7", 14570), {&byte, 1}));
  EXPECT_EQ(ep->stats().send_errors, 4u);
  EXPECT_EQ(ep->stats().datagrams_out, 0u);
  EXPECT_EQ(ep->stats().last_send_errno, EINVAL);
  const auto said = ep->take_send_errors();
  ASSERT_EQ(said.size(), 2u);
  EXPECT_NE(said[0].find("HIL link: cannot send to 192.0.2.1:14560"), std::string::npos) << said[0];
  EXPECT_NE(said[1].find("192.0.2.7:14570"), std::string::npos) << said[1];
  EXPECT_TRUE(ep->take_send_errors().empty());
  // queue() keeps the new frame even when sending the full batch before it failed.
  for (int i = 0; i < 30; ++i) {
    const std::vector<uint8_t> frame(60, 1);
    (void)ep->queue(frame);
  }
  EXPECT_GT(ep->queued_bytes(), 0u);
  EXPECT_LE(ep->queued_bytes(), UdpEndpoint::kMaxDatagram);
}

}  // namespace
}  // namespace hitl::net
