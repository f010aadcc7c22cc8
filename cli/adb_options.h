// --adb, --adb-serial, --adb-relay: the commands that reach the board through adb (hitl sim,
// hitl bridge) share these options and this one way of opening the tunnel (engine/net/adb_tunnel.h).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>

#include "cli/common_options.h"
#include "engine/net/adb_tunnel.h"

namespace hitl::cli {

struct AdbOptions {
  bool adb = false;          ///< --adb: reach the board through adb (USB) instead of its IP
  std::string serial;        ///< --adb-serial S (implies --adb)
  std::string relay_binary;  ///< --adb-relay FILE: the hitl-adb-relay to push when the board has none
  bool enabled() const { return adb || !serial.empty(); }
};

/// Adds --adb, --adb-serial and --adb-relay to `command` in `group`; returns the --adb option (for excludes()).
CLI::Option* add_adb_options(CLI::App& command, AdbOptions& options, const std::string& group);

/// Opens the tunnel with progress and link changes on stderr ("hitl <command>: adb tunnel: ...").
Expected<std::unique_ptr<net::AdbTunnel>> open_adb_tunnel(const GlobalOptions& global, const std::string& command,
                                                         const AdbOptions& options);

/// The tunnel's counters for --json: {"serial", "forward_port", "connected", "connects", "link_losses",
/// "rtt_ms", "rtt_max_ms", "last_error", "channels": {"HIL": {...}, "VIO": {...}, "GCS": {...}}}.
nlohmann::json adb_tunnel_json(const net::AdbTunnel& tunnel);
/// One human line of the same.
std::string adb_tunnel_line(const net::AdbTunnel& tunnel);

}  // namespace hitl::cli
