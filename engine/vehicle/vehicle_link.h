// How every board-operating command reaches the flight stack (DESIGN.md §4):
//   auto (default): through a running `hitl sim` / `hitl bridge` session's client port
//     (127.0.0.1:14600) when one answers; else straight to the board's GCS instance (-i IP, 14558)
//     from the fixed local port 14562. Never the HIL port and never an ephemeral local port: a PX4
//     MAVLink instance answers only the first address and port it heard, for the life of its process.
// or a link in the one grammar (engine/net/link_spec.h):
//   udp:HOST:PORT       talk to that address from --local-port (default 14562)
//   udpin:[HOST:]PORT   listen on PORT and answer whoever talks first
//   tcp:HOST:PORT       a TCP MAVLink server (mavlink-router, MAVProxy, PX4 started with -t)
//   tcpin:[HOST:]PORT   listen on TCP PORT for the autopilot's side to connect (within --timeout)
// The autopilot is discovered from its HEARTBEAT (autopilot != MAV_AUTOPILOT_INVALID).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "base/common/expected.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/net/link.h"
#include "base/contract/board_ports.h"

namespace hitl::vehicle {

using ::hitl::kBoardGcsPort;     // the port table: base/contract/board_ports.h
using ::hitl::kDirectLocalPort;  // direct commands always talk from here

struct LinkOptions {
  std::string connect = "auto";           ///< --connect
  std::string target_ip = "127.0.0.1";    ///< -i: the board for auto's direct path
  uint16_t gcs_port = kBoardGcsPort;      ///< --port: the board's GCS instance
  uint16_t local_port = kDirectLocalPort; ///< --local-port
  uint16_t session_port = kSessionClientPort;  ///< a running session's client port
  std::optional<uint8_t> sysid;           ///< --sysid: pick this autopilot among several
  double timeout_s = 5.0;                 ///< --timeout: discovery
  uint8_t own_sysid = 255;                ///< our identity: a ground station
  uint8_t own_compid = 190;
  /// When set and true, every wait (discovery too) ends within 0.2 s: a dashboard quitting does not
  /// wait out a discovery timeout.
  const std::atomic<bool>* stop = nullptr;
};

class VehicleLink {
 public:
  using FrameHandler = std::function<bool(const mavlink::Frame&)>;  ///< returns true when done

  static Expected<std::unique_ptr<VehicleLink>> connect(const LinkOptions& options);

  template <class M>
  void send(const M& message) {
    mavlink::FrameBuffer buf;
    const std::size_t n = encoder_.encode(message, buf);
    send_bytes({buf.data(), n});
  }
  /// Reads frames from the target system for up to `timeout_s` (sending our HEARTBEAT each
  /// second); true as soon as `handler` returns true.
  bool wait(double timeout_s, const FrameHandler& handler);
  /// Frames from other systems seen during wait() (e.g. the simulator's ground truth, sysid 250,
  /// when connected through a session); none by default.
  void on_other_systems(std::function<void(const mavlink::Frame&)> handler) { other_systems_ = std::move(handler); }
  /// Every frame read (any system) and sent from now on, as its bytes (a recording); none by default.
  void record_frames(std::function<void(std::span<const uint8_t>)> sink) { record_ = std::move(sink); }

  uint8_t target_sysid() const { return sysid_; }
  uint8_t target_compid() const { return compid_; }
  /// "through the session on 127.0.0.1:14600" / "direct to 192.168.101.2:14558 from port 14562"
  const std::string& description() const { return description_; }

 private:
  VehicleLink(std::unique_ptr<net::Link> link, const LinkOptions& options, std::string description);
  void send_bytes(std::span<const uint8_t> bytes);
  std::string send_error_;  ///< the first refused send (UDP), said when no answer came
  void heartbeat();
  bool discover(double timeout_s);

  std::unique_ptr<net::Link> link_;  ///< UDP (auto, udp:, udpin:) or TCP (tcp:, tcpin:; a lost connection stays closed)
  mavlink::MessageSet messages_;
  mavlink::FrameParser parser_;
  mavlink::FrameEncoder encoder_;
  LinkOptions options_;
  std::string description_;
  uint8_t sysid_ = 0;
  uint8_t compid_ = 0;
  double last_heartbeat_s_ = -1e9;
  std::function<void(const mavlink::Frame&)> other_systems_;
  std::function<void(std::span<const uint8_t>)> record_;
};

}  // namespace hitl::vehicle
