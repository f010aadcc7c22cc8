// What the host checks look at: the network interfaces (getifaddrs) and who holds a UDP port
// (a bind attempt, then /proc/net/udp{,6} for the socket's inode and /proc/PID/fd for its owner).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/doctor/host_checks.h"

namespace hitl::doctor {

/// The IPv4 addresses of every interface.
std::vector<NetInterface> list_interfaces();

/// Tries to bind UDP `port` on every address (and closes it at once); when that fails with
/// EADDRINUSE, names the processes holding it where /proc lets this user see them.
PortProbe probe_udp_port(uint16_t port, const std::string& role);

/// The socket inodes bound to local UDP `port` in /proc/net/udp-format `table` text.
std::vector<uint64_t> udp_inodes_for_port(const std::string& table, uint16_t port);

}  // namespace hitl::doctor
