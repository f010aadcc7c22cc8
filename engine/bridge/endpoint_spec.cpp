#include "engine/bridge/endpoint_spec.h"

#include "engine/net/socket_address.h"

namespace hitl::bridge {

namespace {

/// The options after '?' (only `lossless` today), kept apart from the address grammar.
Status parse_endpoint_options(std::string_view options, EndpointSpec& spec, const std::string& what) {
  if (options != "lossless")
    return Error::input(what + ": unknown option '" + std::string(options) + "' (lossless)");
  if (spec.kind == EndpointSpec::Kind::Tcp)
    return Error::input(what + ": a tcp: endpoint loses nothing already (the stream waits for its reader); "
                               "?lossless is for udp: and udpin:");
  spec.lossless = true;
  return Ok{};
}

Expected<EndpointSpec> parse_address(std::string_view text);

}  // namespace

Expected<EndpointSpec> parse_endpoint(std::string_view text) {
  const auto question = text.find('?');
  auto spec = parse_address(text.substr(0, question));
  if (!spec) return spec.error();
  spec->text = std::string(text);
  if (question != std::string_view::npos) {
    if (auto st = parse_endpoint_options(text.substr(question + 1), *spec, "'" + spec->text + "'"); !st) return st.error();
  }
  return spec;
}

namespace {

Expected<EndpointSpec> parse_address(std::string_view text) {
  EndpointSpec spec;
  spec.text = std::string(text);
  const std::string what = "'" + spec.text + "'";  // the value, not the option it came from
  const auto colon = text.find(':');
  if (colon == std::string_view::npos)
    return Error::input(what + ": expected udp:HOST:PORT, udpin:PORT or tcp:HOST:PORT");
  const std::string_view scheme = text.substr(0, colon);
  const std::string_view rest = text.substr(colon + 1);
  if (scheme == "udpin") {
    auto port = net::parse_port(rest, what);
    if (!port) return port.error();
    spec.kind = EndpointSpec::Kind::UdpIn;
    spec.port = *port;
    return spec;
  }
  if (scheme != "udp" && scheme != "tcp")
    return Error::input(what + ": unknown kind '" + std::string(scheme) + "' (udp, udpin or tcp)");
  const auto last = rest.rfind(':');
  if (last == std::string_view::npos || last == 0)
    return Error::input(what + ": expected " + std::string(scheme) + ":HOST:PORT");
  auto port = net::parse_port(rest.substr(last + 1), what);
  if (!port) return port.error();
  spec.kind = scheme == "udp" ? EndpointSpec::Kind::Udp : EndpointSpec::Kind::Tcp;
  spec.host = std::string(rest.substr(0, last));
  spec.port = *port;
  return spec;
}

}  // namespace

}  // namespace hitl::bridge
