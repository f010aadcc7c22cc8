// The one place a LinkSpec (link_spec.h) becomes a Link (link.h), as mavlink-router creates every
// endpoint kind in one place. What a kind means for one use is in LinkSettings: the board's fixed
// local port, hearing the peer only, reconnecting, how many clients a TCP listener takes.
//
//   udp:HOST:PORT      UdpLink with a fixed peer, sent from settings.local_port
//   udpin:[HOST:]PORT  UdpLink bound there, answering the last sender
//   tcp:HOST:PORT      TcpClientLink (connects in open_link() unless it reconnects by itself)
//   tcpin:[HOST:]PORT  TcpServerLink (one client, for good: PX4 SITL) or, with max_clients > 1,
//                      TcpHubLink (ground station tools come and go)
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "base/common/expected.h"
#include "engine/net/link.h"
#include "engine/net/link_spec.h"
#include "engine/net/udp_link.h"

namespace hitl::net {

struct LinkSettings {
  std::string name = "link";          ///< names the link in errors and events ("--endpoint tcpin:5760")
  std::string host_what;              ///< names the HOST when it cannot be resolved (default: name)
  std::string bind_address = "0.0.0.0";  ///< udp: the local socket's address; udpin, tcpin without HOST
  uint16_t local_port = 0;            ///< udp: the fixed local port to send from (0: ephemeral)
  bool hear_peer_only = false;        ///< udp: drop datagrams from anyone but the peer (counted)
  int receive_buffer_bytes = 1 << 20; ///< udp, udpin: SO_RCVBUF asked for
  int connect_timeout_ms = 500;       ///< tcp
  double reconnect_period_s = 0;      ///< tcp: 0 connects in open_link(), a loss is closed() for good
  std::size_t max_clients = 1;        ///< tcpin: 1 takes one client for good; more: a hub of clients
};

/// Opens what `spec` names: binds, listens or connects. A host that does not resolve, a port in use
/// or a server that does not answer is an Error naming settings.name and the address.
Expected<std::unique_ptr<Link>> open_link(const LinkSpec& spec, const LinkSettings& settings);

/// open_link() for udp: and udpin:, typed: for the owner that reads the socket's own figures (the
/// buffers the kernel granted, SO_MEMINFO's drops: the bridge's board link). tcp: and tcpin: are
/// refused (input).
Expected<std::unique_ptr<UdpLink>> open_udp_link(const LinkSpec& spec, const LinkSettings& settings);

/// Whether something may listen on UDP `address`: false only when the kernel says at once that
/// nothing does (a connected UDP socket gets ICMP port-unreachable as ECONNREFUSED; on loopback
/// within microseconds). `hitl arm`'s auto link asks it before trying a running session.
bool udp_listener_may_be_at(const SocketAddress& address);

/// Whether a socket holds UDP `port` on every interface: binding 0.0.0.0:port says EADDRINUSE (true)
/// or succeeds (false; the socket is closed at once). Any other refusal is an Error (unavailable)
/// naming the port. `hitl doctor` asks it before looking for the holders in /proc.
Expected<bool> udp_port_in_use(uint16_t port);

}  // namespace hitl::net
