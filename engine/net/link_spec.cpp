#include "engine/net/link_spec.h"

#include <algorithm>
#include <iterator>

#include "engine/net/socket_address.h"

namespace hitl::net {
namespace {

struct KindName {
  std::string_view name;
  LinkSpec::Kind kind;
};
constexpr KindName kKinds[] = {{"udp", LinkSpec::Kind::Udp},
                               {"udpin", LinkSpec::Kind::UdpIn},
                               {"tcp", LinkSpec::Kind::Tcp},
                               {"tcpin", LinkSpec::Kind::TcpIn}};

/// "HOST:PORT", "[V6]:PORT" or, when `port_only_allowed`, "PORT": the host ("" when not given) and
/// the port text.
Expected<std::pair<std::string, std::string_view>> split_host_port(std::string_view rest, const std::string& what,
                                                                    std::string_view kind, bool port_only_allowed) {
  const std::string expected = std::string(kind) + (port_only_allowed ? ":[HOST:]PORT" : ":HOST:PORT");
  if (!rest.empty() && rest.front() == '[') {
    const auto close = rest.find(']');
    if (close == std::string_view::npos || close + 1 >= rest.size() || rest[close + 1] != ':' || close == 1)
      return Error::input(what + ": expected " + expected + " (an IPv6 address in brackets: [::1]:PORT)");
    return std::pair{std::string(rest.substr(1, close - 1)), rest.substr(close + 2)};
  }
  const auto colon = rest.rfind(':');
  if (colon == std::string_view::npos) {
    if (!port_only_allowed) return Error::input(what + ": expected " + expected);
    return std::pair{std::string(), rest};
  }
  if (colon == 0) return Error::input(what + ": expected " + expected + " (the HOST is empty)");
  if (rest.substr(0, colon).find(':') != std::string_view::npos)
    return Error::input(what + ": expected " + expected + " (an IPv6 address goes in brackets: [::1]:PORT)");
  return std::pair{std::string(rest.substr(0, colon)), rest.substr(colon + 1)};
}

}  // namespace

const char* kind_name(LinkSpec::Kind kind) {
  switch (kind) {
    case LinkSpec::Kind::Udp: return "udp";
    case LinkSpec::Kind::UdpIn: return "udpin";
    case LinkSpec::Kind::Tcp: return "tcp";
    case LinkSpec::Kind::TcpIn: return "tcpin";
  }
  return "udp";
}

std::string LinkSpec::to_string() const {
  std::string out = std::string(kind_name(kind)) + ":";
  const bool brackets = host.find(':') != std::string::npos || (!host.empty() && host.front() == '[');
  if (!host.empty()) out += (brackets ? "[" + host + "]" : host) + ":";
  return out + std::to_string(port) + (lossless ? "?lossless" : "");
}

Expected<LinkSpec> parse_link_spec(std::string_view whole, LinkSpecOptions allowed) {
  LinkSpec spec;
  spec.text = std::string(whole);
  const std::string what = "'" + spec.text + "'";  // the value; the caller names the option
  const auto question = whole.find('?');
  const std::string_view text = whole.substr(0, question);
  const std::string_view options = question == std::string_view::npos ? std::string_view{} : whole.substr(question + 1);
  const auto colon = text.find(':');
  if (colon == std::string_view::npos) return Error::input(what + ": expected " + std::string(kLinkGrammar));
  const std::string_view scheme = text.substr(0, colon);
  const KindName* found = nullptr;
  for (const auto& k : kKinds)
    if (k.name == scheme) found = &k;
  if (found == nullptr)
    return Error::input(what + ": unknown kind '" + std::string(scheme) + "' (udp, udpin, tcp or tcpin: " + kLinkGrammar + ")");
  spec.kind = found->kind;
  auto parts = split_host_port(text.substr(colon + 1), what, scheme, spec.listens());
  if (!parts) return parts.error();
  auto port = parse_port(parts->second, what);
  if (!port) return port.error();
  spec.host = std::move(parts->first);
  spec.port = *port;
  if (question != std::string_view::npos) {
    if (!allowed.lossless) return Error::input(what + ": this option takes no '?' options");
    if (options != "lossless") return Error::input(what + ": unknown option '" + std::string(options) + "' (lossless)");
    if (spec.stream())
      return Error::input(what + ": a tcp: or tcpin: link loses nothing already (the stream waits for its reader); "
                                 "?lossless is for udp: and udpin:");
    spec.lossless = true;
  }
  return spec;
}

Expected<LinkSpec> parse_udp_peer(std::string_view text, std::string_view why_udp) {
  const auto colon = text.find(':');
  const std::string_view scheme = colon == std::string_view::npos ? std::string_view{} : text.substr(0, colon);
  const bool spelled_as_link = std::any_of(std::begin(kKinds), std::end(kKinds), [&](const KindName& k) { return k.name == scheme; });
  auto spec = parse_link_spec(spelled_as_link ? std::string(text) : "udp:" + std::string(text));
  if (!spec) {
    if (spelled_as_link) return spec.error();
    return Error::input("'" + std::string(text) + "': expected udp:HOST:PORT or HOST:PORT");
  }
  spec->text = std::string(text);
  if (spec->kind != LinkSpec::Kind::Udp)
    return Error::input("'" + spec->text + "': " + std::string(why_udp) + ": udp:HOST:PORT (or HOST:PORT)");
  return spec;
}

}  // namespace hitl::net
