// hitl bridge: the board link without the simulator. Owns the connection to the board's GCS
// MAVLink instance (from the fixed local port 14562: PX4 answers only the first sender it heard),
// and routes with the session's router between it, local clients on 127.0.0.1:14600 and any
// --endpoint links. Once a second it reports link health: partner, packets and bytes each way,
// per-source loss, round-trip time (TIMESYNC, as PX4 answers it) and the age of the board's last
// HEARTBEAT; it says within 2 s when the board goes away and when it comes back, and keeps every
// socket open meanwhile so clients and traffic resume by themselves. The board link hears only the
// board's address (anything else is dropped unparsed and counted), and the loss table is bounded.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/common/severity.h"
#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "engine/net/link_spec.h"
#include "engine/telemetry/dsp_hitl_meter.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::bridge {

inline constexpr uint8_t kBridgeSystemId = 255;        ///< with compid MAV_COMP_ID_UDP_BRIDGE
inline constexpr uint8_t kBridgeComponentId = 240;
inline constexpr double kBoardGoneAfter_s = 1.5;       ///< no frame this long: gone (HEARTBEAT is 1 Hz)
inline constexpr std::size_t kMaxLossSources = 32;     ///< per-source loss kept for at most this many sysid/compid

struct BridgeConfig {
  std::string board_ip = "127.0.0.1";               ///< -i (a VOXL2 on USB-Ethernet: 192.168.101.2)
  uint16_t board_port = vehicle::kBoardGcsPort;     ///< --port: the board's GCS MAVLink instance
  uint16_t local_port = vehicle::kDirectLocalPort;  ///< --local-port: fixed (PX4's partner lock)
  std::string clients_bind = "127.0.0.1";
  uint16_t clients_port = hitl::kSessionClientPort;  ///< --clients (0: none)
  std::vector<net::LinkSpec> endpoints;    ///< --endpoint (udp:, udpin:, tcp: reconnecting, tcpin: many clients)
  double dedup_window_s = 0.1;             ///< --dedup (0: off)
  double duration_s = 0;                   ///< --duration (0: until stopped)
  double health_period_s = 1.0;
  /// --queue-ms: the most the clients' queue holds back under overload, in milliseconds of their
  /// measured sending time (at least kMinClientQueueFrames, and at least what one loop turn sends);
  /// beyond it the oldest frames are dropped and counted. The board socket's receive buffer holds
  /// kBoardBuffer_ms of the board's measured stream (within kBoardReceiveMin/Max_bytes).
  /// `?lossless` endpoints are never dropped to (the board waits in its socket for them instead).
  double queue_ms = 20;
  /// What the board's dsp_hitl counters should show (the dashboard's dsp_hitl panel). The bridge runs
  /// no simulator and never sees the HIL traffic (it goes to the board's HIL port), so the spec's
  /// table: whatever feeds the board is expected to send at the spec's rates.
  telemetry::DspHitlExpectedRates dsp_hitl_rates = telemetry::spec_dsp_hitl_expected_rates();
};

inline constexpr double kBoardBuffer_ms = 2;              ///< of the board's stream, as read: the board is read as fast as it sends
inline constexpr int kBoardReceiveMin_bytes = 64 << 10;   ///< asked for at least (the kernel doubles it: ~157 small datagrams on loopback, 157 ms at 1,000/s)
inline constexpr int kBoardReceiveMax_bytes = 1 << 20;    ///< asked for at most
inline constexpr std::size_t kMinClientQueueFrames = 32;  ///< the clients' queue never holds fewer (a stall of the loop is not overload)
inline constexpr std::size_t kMaxLosslessQueueFrames = 4096;  ///< a ?lossless endpoint's frames waiting for its send buffer

struct SourceLoss {
  uint64_t received = 0;
  uint64_t lost = 0;
  double loss_pct = 0;
};

struct LinkHealth {
  std::string name;     ///< "board", "clients", "udp:127.0.0.1:14550" (an --endpoint as given)
  std::string partner;  ///< peer address, or "" when none yet
  bool connected = false;
  uint64_t packets_in = 0, bytes_in = 0, packets_out = 0, bytes_out = 0, duplicates_in = 0;
  uint64_t send_errors = 0;  ///< packets the kernel refused to send (not in packets_out)
  uint64_t dropped = 0;      ///< clients: frames routed here that found the send queue full (never sent)
  uint64_t deliveries = 0;   ///< clients: datagrams sent, one per frame and client
  uint64_t send_buffer_full = 0;  ///< clients: sends that found the socket buffer full and waited (not lost)
  uint64_t kernel_rx_drops = 0;   ///< datagrams the kernel dropped before the bridge read them (receive buffer full)
  bool lossless = false;          ///< a ?lossless endpoint: never dropped to
  /// `dropped` by message name ("ATTITUDE"; an id without a name by its number; "other" beyond 64 ids)
  std::map<std::string, uint64_t> dropped_by_message;
};

struct BridgeHealth {
  double uptime_s = 0;
  std::string board_state;  ///< "waiting" (never heard), "up", "gone"
  std::optional<double> heartbeat_age_s;
  std::optional<double> rtt_ms;                ///< last TIMESYNC round trip
  std::map<std::string, SourceLoss> loss;      ///< per board source "sysid/compid"
  std::vector<LinkHealth> links;               ///< board first, then clients, then endpoints
  std::size_t clients = 0;
  uint64_t duplicates = 0;
  uint64_t ignored_other_address = 0;  ///< datagrams on the board link not from the board, or on a udp: endpoint not from its peer
  uint64_t untracked_frames = 0;       ///< board frames from sources beyond kMaxLossSources (not in `loss`)
  uint64_t kernel_rx_drops = 0;        ///< board datagrams the kernel dropped before the bridge read them (SO_RXQ_OVFL / SO_MEMINFO, read each report)
  int board_receive_buffer_bytes = 0;  ///< granted now (sized to --queue-ms of the board's stream)
};

class BridgeObserver {
 public:
  virtual ~BridgeObserver() = default;
  virtual void on_event(const std::string& text, Severity severity) = 0;
  virtual void on_health(const BridgeHealth& health) = 0;
};

/// Runs until `stop` is set, the duration ends, or an error (a port in use, a bad address).
/// `opened` (when given) turns true once every socket is open: an error before that is bad input
/// (a port in use, a bad address: exit 2), one after it is the link's (exit 1).
Status run_bridge(const BridgeConfig& config, BridgeObserver& observer, const std::atomic<bool>& stop, bool* opened = nullptr);

}  // namespace hitl::bridge
