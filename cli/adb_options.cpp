#include "cli/adb_options.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace hitl::cli {
namespace {

/// hitl-adb-relay beside the running hitl (an install), then the one this build made.
std::vector<std::string> default_relay_binaries() {
  std::vector<std::string> paths;
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back((self.parent_path() / adb::kRelayProgram).string());
#ifdef HITL_ADB_RELAY_BUILD_PATH
  paths.push_back(HITL_ADB_RELAY_BUILD_PATH);
#endif
  return paths;
}

}  // namespace

CLI::Option* add_adb_options(CLI::App& command, AdbOptions& options, const std::string& group) {
  auto* adb = command.add_flag("--adb", options.adb,
                               "Reach the board through adb (USB) instead of its IP: the UDP ports go through "
                               "hitl-adb-relay over `adb forward` (docs/adb.md)")
                  ->group(group);
  command.add_option("--adb-serial", options.serial, "With several devices attached: the board's adb serial (implies --adb)")
      ->type_name("SERIAL")->group(group);
  command.add_option("--adb-relay", options.relay_binary,
                     "The hitl-adb-relay to push when the board has none, built for the board (default: the one "
                     "beside hitl, then this build's)")
      ->check(CLI::ExistingFile)->type_name("FILE")->group(group);
  return adb;
}

Expected<std::unique_ptr<net::AdbTunnel>> open_adb_tunnel(const GlobalOptions& global, const std::string& command,
                                                         const AdbOptions& options) {
  net::AdbTunnelConfig config;
  config.serial = options.serial;
  if (!options.relay_binary.empty()) config.relay_binaries.push_back(options.relay_binary);
  for (auto& path : default_relay_binaries()) config.relay_binaries.push_back(std::move(path));
  const bool quiet = global.quiet;
  config.tunnel.on_event = [command, quiet](const std::string& line) {
    // Link changes are worth a line even with -q: the board stops answering while it lasts.
    if (quiet && line.find("link") == std::string::npos) return;
    std::cerr << "hitl " + command + ": " + line + "\n" << std::flush;
  };
  return net::AdbTunnel::open(config);
}

nlohmann::json adb_tunnel_json(const net::AdbTunnel& tunnel) {
  const auto s = tunnel.stats();
  nlohmann::json channels = nlohmann::json::object();
  for (adb::Channel c : adb::kDataChannels) {
    const auto& k = s.channels[adb::index_of(c)];
    channels[adb::to_string(c)] = {{"local", tunnel.local_endpoint(c).to_string()},
                                   {"to_board", k.to_board},
                                   {"from_board", k.from_board},
                                   {"bytes_to_board", k.bytes_to_board},
                                   {"bytes_from_board", k.bytes_from_board},
                                   {"dropped", {{"no_link", k.dropped_no_link},
                                                {"backlog", k.dropped_backlog},
                                                {"too_large", k.dropped_too_large},
                                                {"no_client", k.dropped_no_client}}}};
  }
  nlohmann::json j = {{"serial", tunnel.serial()},
                      {"forward_port", tunnel.forward_port()},
                      {"connected", s.connected},
                      {"connects", s.connects},
                      {"link_losses", s.link_losses},
                      {"rtt_max_ms", s.rtt_max_ms},
                      {"last_error", s.last_error},
                      {"channels", channels}};
  j["rtt_ms"] = s.rtt_ms ? nlohmann::json(*s.rtt_ms) : nlohmann::json(nullptr);
  return j;
}

std::string adb_tunnel_line(const net::AdbTunnel& tunnel) {
  const auto s = tunnel.stats();
  char rtt[64] = "no round trip yet";
  if (s.rtt_ms) std::snprintf(rtt, sizeof rtt, "round trip %.2f ms (max %.2f)", *s.rtt_ms, s.rtt_max_ms);
  std::string line = "adb tunnel (board " + tunnel.serial() + "): " + (s.connected ? "up" : "down") + ", " +
                     std::to_string(s.connects) + " connect(s), " + std::to_string(s.link_losses) + " loss(es), " + rtt;
  for (adb::Channel c : adb::kDataChannels) {
    const auto& k = s.channels[adb::index_of(c)];
    const uint64_t dropped = k.dropped_no_link + k.dropped_backlog + k.dropped_too_large + k.dropped_no_client;
    line += std::string("; ") + adb::to_string(c) + " " + std::to_string(k.to_board) + " out, " + std::to_string(k.from_board) +
            " in" + (dropped ? ", " + std::to_string(dropped) + " dropped" : "");
  }
  return line;
}

}  // namespace hitl::cli
