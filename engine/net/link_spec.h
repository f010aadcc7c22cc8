// One grammar for every MAVLink link a user names: `--connect`, `hitl bridge --endpoint`,
// `hitl sim --px4-sitl` and their keys in the config file, as mavlink-router and MAVProxy name them:
//
//   udp:HOST:PORT       send to HOST:PORT (a listener: QGroundControl on 14550, the board); its
//                       answers come back to our socket
//   udpin:[HOST:]PORT   listen on UDP PORT (HOST: the local address, default every interface) and
//                       answer whoever spoke last
//   tcp:HOST:PORT       connect to a TCP server (mavlink-router's 5760, MAVProxy, PX4 started with -t)
//   tcpin:[HOST:]PORT   listen on TCP PORT; clients connect (ground station tools, PX4 SITL)
//
// A udp: or udpin: link may end in `?lossless` where the option takes it (hitl bridge --endpoint: a
// recorder gets every frame taken in, never dropped to keep it fresh); elsewhere it is refused.
// HOST is a name or an address, an IPv6 one in brackets ([::1]). What a kind means for one option
// (the board's local port, reconnecting, how many clients) is the option's: open_link() takes it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/common/expected.h"

namespace hitl::net {

/// The four kinds, as the user spells them: in help texts and errors.
inline constexpr const char* kLinkGrammar = "udp:HOST:PORT, udpin:[HOST:]PORT, tcp:HOST:PORT or tcpin:[HOST:]PORT";

struct LinkSpec {
  enum class Kind { Udp, UdpIn, Tcp, TcpIn };
  Kind kind = Kind::Udp;
  std::string host;  ///< udp, tcp: the peer; udpin, tcpin: the local address ("" when not given)
  uint16_t port = 0;
  std::string text;  ///< as given, for messages
  bool lossless = false;  ///< ?lossless: every frame, waiting for a full send buffer (a recorder)

  /// udpin, tcpin: the other end starts the conversation.
  bool listens() const { return kind == Kind::UdpIn || kind == Kind::TcpIn; }
  /// tcp, tcpin: a byte stream.
  bool stream() const { return kind == Kind::Tcp || kind == Kind::TcpIn; }
  /// The spelling the grammar gives it ("udpin:14550", "tcp:127.0.0.1:5760").
  std::string to_string() const;
};

/// "udp", "udpin", "tcp", "tcpin".
const char* kind_name(LinkSpec::Kind kind);

/// What the option that parses a link takes after '?' (nothing unless it says so).
struct LinkSpecOptions {
  bool lossless = false;
};

/// Parses one link as the grammar above spells it. The Error (kind input) names the value and what is
/// wrong with it; the caller adds the option it came from ("--endpoint 'x': ...").
Expected<LinkSpec> parse_link_spec(std::string_view text, LinkSpecOptions allowed = {});

/// A UDP peer, for the options that can only send to one (inspect --connect, sim --gcs): the
/// grammar's udp:HOST:PORT, or HOST:PORT as those options took it before. Any other kind is refused
/// (input), saying `why_udp` ("inspect times UDP datagrams as the kernel received them").
Expected<LinkSpec> parse_udp_peer(std::string_view text, std::string_view why_udp);

}  // namespace hitl::net
