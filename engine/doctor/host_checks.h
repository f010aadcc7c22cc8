// The host's part of the spec's Troubleshooting ("Check UDP connectivity", "Ensure ... resolved the
// correct VOXL2 IP", "adb devices"): decisions on what host_probe.h and adb.h observed. Pure.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/doctor/check_result.h"
#include "engine/net/adb_client.h"

namespace hitl::doctor {

/// One IPv4 address of a network interface (getifaddrs), host byte order.
struct NetInterface {
  std::string name;        ///< "usb0", "enx0a1b2c3d4e5f"
  uint32_t address = 0;
  uint32_t netmask = 0;
  bool up = false;         ///< IFF_UP
  bool running = false;    ///< IFF_RUNNING: carrier
};

/// "192.168.101.2" -> its host-order IPv4 address; nullopt for anything else.
std::optional<uint32_t> parse_ipv4(const std::string& text);
std::string format_ipv4(uint32_t address);

/// route: an interface up with an address in the board's subnet (`board_ip` as given to -i).
/// Loopback boards (hitl target, an adb tunnel) are skipped.
CheckResult route_check(const std::string& board_ip, const std::vector<NetInterface>& interfaces);

/// adb: only with --adb; `listing` is `adb devices` (engine/net/adb_client.h) or why adb could not run.
CheckResult adb_check(bool wanted, const std::string& serial, const Expected<net::AdbDevices>& listing);

/// A process holding a UDP port (from /proc).
struct PortHolder {
  int pid = 0;
  std::string command;  ///< the program and its first argument that is not an option: "hitl target"
  std::string name;     ///< the program's file name: "hitl", "python3"
};

struct PortProbe {
  uint16_t port = 0;
  std::string role;                 ///< "HIL", "VIO"
  bool taken = false;               ///< binding it failed with EADDRINUSE
  std::vector<PortHolder> holders;  ///< who holds it, when /proc tells (empty: unknown)
  std::string error;                ///< the probe itself failed (not EADDRINUSE)
};

/// Programs that stand in for the board on this host and so may hold its ports: hitl (target),
/// hitl-adb-relay, adb, px4, voxl-hitl-vio-server.
bool is_board_stand_in(const PortHolder& holder);

/// ports: with a remote board the board's HIL and VIO ports must be free on this host (another
/// process there, e.g. the spec's Phase 1 Python listener, takes what a local tool sends); with the
/// board on this host (127.0.0.1) they must be held by the board's stand-in.
CheckResult ports_check(const std::vector<PortProbe>& probes, bool board_on_this_host);

/// True for 127.0.0.0/8 and "localhost".
bool is_loopback_host(const std::string& host);

}  // namespace hitl::doctor
