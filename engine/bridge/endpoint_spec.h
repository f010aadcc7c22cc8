// An extra link for `hitl bridge --endpoint`, as mavlink-router's endpoints:
//   udp:HOST:PORT   send to a listener (QGroundControl on 14550), answers come back to our socket
//   udpin:PORT      listen on PORT, answer whoever spoke last (MAVProxy --out udp:...)
//   tcp:HOST:PORT   connect to a TCP server (MAVProxy, SITL), reconnecting when it goes away
// A udp: or udpin: endpoint may end in `?lossless` (a recorder): it gets every frame the bridge
// takes in, never dropped to keep it fresh (parse_endpoint_options, apart from the address grammar).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/common/expected.h"

namespace hitl::bridge {

struct EndpointSpec {
  enum class Kind { Udp, UdpIn, Tcp };
  Kind kind = Kind::Udp;
  std::string host;  ///< empty for udpin
  uint16_t port = 0;
  std::string text;  ///< as given, for messages
  bool lossless = false;  ///< ?lossless: every frame taken in, waiting for a full send buffer (a recorder)
};

/// Parses one --endpoint value; the Error names the value and what is wrong with it.
Expected<EndpointSpec> parse_endpoint(std::string_view text);

}  // namespace hitl::bridge
