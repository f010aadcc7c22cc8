// Why a datagram could not be sent, in words a user can act on: the errno's text and the likely
// fix (no route to a 192.168.101.x board: give this host an address on its USB-Ethernet, as
// `hitl doctor`'s route check says).
#pragma once

#include <string>

#include "engine/net/socket_address.h"

namespace hitl::net {

/// The likely fix for `error` (an errno from sendto) when sending from `local` to `to`; empty when
/// there is nothing better to say than the errno's text.
std::string send_error_hint(int error, const SocketAddress& local, const SocketAddress& to);

/// "cannot send to 192.168.101.2:14560: Network is unreachable (errno ENETUNREACH); <hint>".
std::string describe_send_error(int error, const SocketAddress& local, const SocketAddress& to);

}  // namespace hitl::net
