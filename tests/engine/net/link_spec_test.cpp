// The one link grammar (engine/net/link_spec.h): the four kinds, HOST optional for the listening
// ones, IPv6 in brackets, and every malformed value refused as input naming the value.
#include <gtest/gtest.h>

#include "engine/net/link_spec.h"

namespace hitl::net {
namespace {

TEST(LinkSpec, ParsesTheFourKinds) {
  auto udp = parse_link_spec("udp:127.0.0.1:14550");
  ASSERT_TRUE(udp.ok()) << udp.error().message;
  EXPECT_EQ(udp->kind, LinkSpec::Kind::Udp);
  EXPECT_EQ(udp->host, "127.0.0.1");
  EXPECT_EQ(udp->port, 14550);
  EXPECT_FALSE(udp->listens());
  EXPECT_FALSE(udp->stream());

  auto udpin = parse_link_spec("udpin:14551");
  ASSERT_TRUE(udpin.ok());
  EXPECT_EQ(udpin->kind, LinkSpec::Kind::UdpIn);
  EXPECT_EQ(udpin->host, "");  // every interface: the caller's default
  EXPECT_EQ(udpin->port, 14551);
  EXPECT_TRUE(udpin->listens());

  auto udpin_host = parse_link_spec("udpin:127.0.0.1:14551");
  ASSERT_TRUE(udpin_host.ok());
  EXPECT_EQ(udpin_host->host, "127.0.0.1");

  auto tcp = parse_link_spec("tcp:localhost:5760");
  ASSERT_TRUE(tcp.ok());
  EXPECT_EQ(tcp->kind, LinkSpec::Kind::Tcp);
  EXPECT_EQ(tcp->host, "localhost");
  EXPECT_TRUE(tcp->stream());

  auto tcpin = parse_link_spec("tcpin:5760");
  ASSERT_TRUE(tcpin.ok());
  EXPECT_EQ(tcpin->kind, LinkSpec::Kind::TcpIn);
  EXPECT_EQ(tcpin->port, 5760);
  EXPECT_TRUE(tcpin->listens());
  EXPECT_TRUE(tcpin->stream());
  EXPECT_EQ(tcpin->text, "tcpin:5760");
}

TEST(LinkSpec, Ipv6HostsGoInBrackets) {
  auto v6 = parse_link_spec("udp:[::1]:14550");
  ASSERT_TRUE(v6.ok()) << v6.error().message;
  EXPECT_EQ(v6->host, "::1");
  EXPECT_EQ(v6->to_string(), "udp:[::1]:14550");
  auto in = parse_link_spec("tcpin:[::]:5760");
  ASSERT_TRUE(in.ok());
  EXPECT_EQ(in->host, "::");
  auto bare = parse_link_spec("udp:::1:14550");
  ASSERT_FALSE(bare.ok());
  EXPECT_NE(bare.error().message.find("brackets"), std::string::npos) << bare.error().message;
}

TEST(LinkSpec, SpellsItselfInTheGrammar) {
  EXPECT_EQ(parse_link_spec("udpin:14550")->to_string(), "udpin:14550");
  EXPECT_EQ(parse_link_spec("tcp:127.0.0.1:5760")->to_string(), "tcp:127.0.0.1:5760");
  EXPECT_EQ(std::string(kind_name(LinkSpec::Kind::TcpIn)), "tcpin");
}

TEST(LinkSpec, MalformedValuesAreInputNamingTheValue) {
  for (const char* bad : {"14550", "serial:/dev/ttyUSB0", "udp:127.0.0.1", "udp:host:99999", "udpin:x", "tcp:5760",
                          "tcpin:", "tcpin:0", "udp::14550", "bogus", "udp:[::1", "TCP:localhost:5760"}) {
    auto e = parse_link_spec(bad);
    ASSERT_FALSE(e.ok()) << bad;
    EXPECT_EQ(e.error().kind, ErrorKind::Input) << bad;
    EXPECT_NE(e.error().message.find(std::string("'") + bad + "'"), std::string::npos) << e.error().message;
  }
  EXPECT_EQ(parse_link_spec("bogus").error().message, "'bogus': expected " + std::string(kLinkGrammar));
  EXPECT_NE(parse_link_spec("serial:/dev/ttyUSB0").error().message.find("unknown kind 'serial'"), std::string::npos);
  EXPECT_NE(parse_link_spec("tcp:5760").error().message.find("expected tcp:HOST:PORT"), std::string::npos);
}

TEST(LinkSpec, AUdpPeerIsTheGrammarsUdpOrHostPortAsBefore) {
  auto spelled = parse_udp_peer("udp:127.0.0.1:14550", "UDP only");
  ASSERT_TRUE(spelled.ok()) << spelled.error().message;
  EXPECT_EQ(spelled->host, "127.0.0.1");
  EXPECT_EQ(spelled->port, 14550);
  auto before = parse_udp_peer("localhost:14550", "UDP only");
  ASSERT_TRUE(before.ok()) << before.error().message;
  EXPECT_EQ(before->kind, LinkSpec::Kind::Udp);
  EXPECT_EQ(before->host, "localhost");
  EXPECT_EQ(before->text, "localhost:14550");
  auto v6 = parse_udp_peer("[::1]:14550", "UDP only");
  ASSERT_TRUE(v6.ok());
  EXPECT_EQ(v6->host, "::1");
  auto tcp = parse_udp_peer("tcp:127.0.0.1:5760", "UDP only");
  ASSERT_FALSE(tcp.ok());
  EXPECT_EQ(tcp.error().kind, ErrorKind::Input);
  EXPECT_EQ(tcp.error().message, "'tcp:127.0.0.1:5760': UDP only: udp:HOST:PORT (or HOST:PORT)");
  for (const char* bad : {"14550", "localhost", "udp:localhost", "host:70000"}) {
    auto e = parse_udp_peer(bad, "UDP only");
    ASSERT_FALSE(e.ok()) << bad;
    EXPECT_NE(e.error().message.find(std::string("'") + bad + "'"), std::string::npos) << e.error().message;
  }
}

}  // namespace
}  // namespace hitl::net

namespace hitl::net {
namespace {

TEST(LinkSpec, LosslessOnlyWhereTheOptionTakesItAndOnlyForUdp) {
  auto plain = parse_link_spec("udp:127.0.0.1:14550?lossless");
  ASSERT_FALSE(plain.ok());  // --connect, --px4-sitl: no '?' options
  EXPECT_EQ(plain.error().kind, ErrorKind::Input);
  EXPECT_NE(plain.error().message.find("takes no '?' options"), std::string::npos) << plain.error().message;
  for (const char* text : {"udp:127.0.0.1:14550?lossless", "udpin:14551?lossless"}) {
    auto ok = parse_link_spec(text, {.lossless = true});
    ASSERT_TRUE(ok.ok()) << text << ": " << ok.error().message;
    EXPECT_TRUE(ok->lossless);
    EXPECT_EQ(ok->to_string(), text);
  }
  EXPECT_FALSE(parse_link_spec("udp:127.0.0.1:14550", {.lossless = true})->lossless);
  auto unknown = parse_link_spec("udp:127.0.0.1:14550?fast", {.lossless = true});
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("unknown option 'fast' (lossless)"), std::string::npos) << unknown.error().message;
  for (const char* stream : {"tcp:127.0.0.1:5760?lossless", "tcpin:5760?lossless"}) {
    auto tcp = parse_link_spec(stream, {.lossless = true});
    ASSERT_FALSE(tcp.ok()) << stream;
    EXPECT_NE(tcp.error().message.find("loses nothing already"), std::string::npos) << tcp.error().message;
  }
  EXPECT_FALSE(parse_link_spec("udp:127.0.0.1:bad?lossless", {.lossless = true}).ok());
}

}  // namespace
}  // namespace hitl::net
