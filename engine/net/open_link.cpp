#include "engine/net/open_link.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/net/tcp_hub_link.h"
#include "engine/net/tcp_links.h"
#include "engine/net/udp_link.h"

namespace hitl::net {
namespace {

template <class L>
Expected<std::unique_ptr<Link>> as_link(Expected<std::unique_ptr<L>> link) {
  if (!link) return link.error();
  return std::unique_ptr<Link>(std::move(link.value()));
}

}  // namespace

Expected<std::unique_ptr<UdpLink>> open_udp_link(const LinkSpec& spec, const LinkSettings& settings) {
  if (spec.stream()) return Error::input(settings.name + ": '" + spec.text + "' is not a UDP link (udp: or udpin:)");
  const std::string& host_what = settings.host_what.empty() ? settings.name : settings.host_what;
  const std::string local_host = spec.host.empty() ? settings.bind_address : spec.host;
  UdpLink::Config c;
  c.endpoint.name = settings.name;
  c.endpoint.receive_buffer_bytes = settings.receive_buffer_bytes;
  if (spec.kind == LinkSpec::Kind::Udp) {
    auto peer = SocketAddress::resolve(spec.host, spec.port);
    if (!peer) return peer.error().prefixed(host_what + ": ");
    c.endpoint.bind_address = settings.bind_address;
    c.endpoint.bind_port = settings.local_port;
    c.endpoint.peer = *peer;
    c.endpoint.policy = PartnerPolicy::Fixed;
    c.hear_peer_only = settings.hear_peer_only;
  } else {
    c.endpoint.bind_address = local_host;
    c.endpoint.bind_port = spec.port;
    c.endpoint.policy = PartnerPolicy::LastSender;
  }
  return UdpLink::open(c);
}

Expected<std::unique_ptr<Link>> open_link(const LinkSpec& spec, const LinkSettings& settings) {
  const std::string& host_what = settings.host_what.empty() ? settings.name : settings.host_what;
  const std::string local_host = spec.host.empty() ? settings.bind_address : spec.host;
  switch (spec.kind) {
    case LinkSpec::Kind::Udp:
    case LinkSpec::Kind::UdpIn: return as_link(open_udp_link(spec, settings));
    case LinkSpec::Kind::Tcp: {
      auto server = SocketAddress::resolve(spec.host, spec.port);
      if (!server) return server.error().prefixed(host_what + ": ");
      TcpClientLink::Config c;
      c.server = *server;
      c.name = settings.name;
      c.connect_timeout_ms = settings.connect_timeout_ms;
      c.reconnect_period_s = settings.reconnect_period_s;
      return as_link(TcpClientLink::open(c));
    }
    case LinkSpec::Kind::TcpIn:
      if (settings.max_clients > 1) return as_link(TcpHubLink::listen(local_host, spec.port, settings.max_clients, settings.name));
      return as_link(TcpServerLink::listen(local_host, spec.port, settings.name));
  }
  return Error::input(settings.name + ": unknown link kind");
}

bool udp_listener_may_be_at(const SocketAddress& address) {
  const int fd = ::socket(address.family(), SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return true;
  bool listening = true;
  const uint8_t probe = 0;  // not a MAVLink frame: a listener counts it as garbage and moves on
  if (::connect(fd, address.get(), address.length()) == 0 && ::send(fd, &probe, 1, 0) == 1) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 50) > 0) {
      uint8_t buf[1];
      if (::recv(fd, buf, sizeof buf, MSG_DONTWAIT) < 0 && errno == ECONNREFUSED) listening = false;
    }
  }
  ::close(fd);
  return listening;
}

Expected<bool> udp_port_in_use(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return Error::unavailable(std::string("cannot open a socket: ") + std::strerror(errno));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_ANY);
  const int err = ::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0 ? 0 : errno;
  ::close(fd);
  if (err == 0) return false;
  if (err == EADDRINUSE) return true;
  return Error::unavailable("cannot bind UDP " + std::to_string(port) + ": " + std::strerror(err));
}

}  // namespace hitl::net
