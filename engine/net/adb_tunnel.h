// The adb path to a VOXL2 (docs/adb.md): `adb forward` carries TCP only, so the board's UDP ports
// (HIL 14560, VIO 14570, GCS 14558) are reached through hitl-adb-relay on the board, over one
// forwarded TCP port, by a DatagramTunnel. AdbTunnel sets that up: finds adb and the board, runs
// `adb forward tcp:0 tcp:14590`, starts the relay with `adb shell` when none answers (pushing it
// with `adb push` when the board has none), and removes the forward when it ends.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/adb_client.h"
#include "engine/net/datagram_tunnel.h"

namespace hitl::net {

struct AdbTunnelConfig {
  std::string serial;                         ///< --adb-serial (empty: the only board attached)
  uint16_t relay_port = adb::kRelayTcpPort;   ///< the relay's TCP port on the board
  /// Host copies of hitl-adb-relay to push when the board has none; the first one built for the
  /// board's architecture (`uname -m`) is pushed. (--adb-relay FILE, then the build's own.)
  std::vector<std::string> relay_binaries;
  int handshake_timeout_ms = 3000;
  DatagramTunnel::Config tunnel;              ///< the pump's periods; on_event also gets the set-up steps
};

class AdbTunnel {
 public:
  /// Sets up the forward and the relay and connects; every failure is an Error that says what to
  /// install, plug in or run. Progress (starting or pushing the relay) goes to config.tunnel.on_event.
  static Expected<std::unique_ptr<AdbTunnel>> open(const AdbTunnelConfig& config);
  /// Stops the tunnel and removes the forward (the relay keeps running on the board for next time).
  ~AdbTunnel();
  AdbTunnel(const AdbTunnel&) = delete;
  AdbTunnel& operator=(const AdbTunnel&) = delete;

  /// Where local code sends to reach the board's port for `channel` ("127.0.0.1:40123").
  const SocketAddress& local_endpoint(adb::Channel channel) const { return tunnel_->local_endpoint(channel); }
  TunnelStats stats() const { return tunnel_->stats(); }
  const std::string& serial() const { return adb_.serial(); }
  /// The host's end of the forward (tcp:PORT), 0 while there is none.
  uint16_t forward_port() const;
  /// "board X through adb forward tcp:41235 -> tcp:14590; HIL 127.0.0.1:40123, VIO ..., GCS ..."
  std::string describe() const;

 private:
  AdbTunnel(const AdbTunnelConfig& config, Adb adb);
  Expected<std::unique_ptr<adb::FramedStream>> establish();
  Status make_forward();
  Status start_relay();
  Expected<std::string> relay_to_push();
  void emit(const std::string& line) const;

  AdbTunnelConfig config_;
  Adb adb_;
  mutable std::mutex forward_mutex_;
  uint16_t forward_port_ = 0;
  std::unique_ptr<DatagramTunnel> tunnel_;
};

}  // namespace hitl::net
