// What the session serves besides the flight stack: the client port (--clients, --gcs) routed to
// and from the board with the bridge's router; once a second the session's own status to clients
// (HEARTBEAT and the NAMED_VALUE_* hitl doctor reads); ground truth to clients (--truth-rate); and
// ODOMETRY to the VIO server (--vio-ip/--vio-port). The client port's work per step is bounded
// (net::ClientPortLimits, docs/sim.md "Clients and load").
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "base/common/expected.h"
#include "engine/faults/fault_schedule.h"
#include "engine/hil/recording.h"
#include "engine/mavlink/statustext.h"
#include "engine/hil/session_config.h"
#include "engine/hil/session_events.h"
#include "engine/hil/stack_link.h"
#include "engine/hil/traffic.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "engine/net/client_port.h"
#include "engine/net/link.h"
#include "engine/router/router.h"
#include "engine/sensors/sensor_suite.h"

namespace hitl::hil {

/// The session's state its status messages carry.
struct SessionStatus {
  bool paused = false;
  double recent_real_time_factor = 0;
  uint64_t late_ticks = 0;
  double actuator_rate_hz = 0;  ///< HIL_ACTUATOR_CONTROLS over the last window (0 when stale)
  std::optional<double> loop_latency_p99_us;  ///< loop_latency.h; none before the first answer
  std::optional<double> loop_latency_p50_us;  ///< the same
  std::optional<double> loop_latency_max_us;  ///< the same
  /// --px4: the instance of the PX4 the session started once it connected, -1 while waiting;
  /// nullopt without --px4 (sim_px4 is then not sent).
  std::optional<int> px4_instance;
};

class ClientServices {
 public:
  /// Opens the client port (when --clients or --gcs) and the VIO link (unless --no-vio).
  static Expected<std::unique_ptr<ClientServices>> open(const SessionConfig& config, const mavlink::MessageSet& messages,
                                                        StackLink& stack, Traffic& traffic, Recording& recording);

  /// Reads the client port (at most kMaxDatagramsPerDrain) and routes to the board and the other clients.
  void drain(double now_s);
  /// A frame from the flight stack: to the clients, unless it is one of the session's own (HIL_*).
  void route_from_stack(const mavlink::Frame& frame, double now_s);
  /// Sends what the step queued for clients and says once when a bound was hit.
  void serve(EventSink& events);

  /// True when send_status() would send (clients are on or a recording runs, and a second of wall
  /// or, for the loop latency, of simulated time has passed): the caller builds the status only then.
  bool status_due(double now_s, double sim_s) const {
    return (clients_.has_value() || recording_.active()) && (now_s >= next_status_wall_s_ || sim_s >= next_latency_sim_s_);
  }
  /// The session's own frames below (status, truth, announcements) go to the clients and into the
  /// recording, so that a recording holds the truth and the session's status (docs/report.md).
  /// Once a second of wall time: HEARTBEAT (STANDBY while paused) and the NAMED_VALUE_* status.
  /// The loop latency's (sim_lat50/99/mx) also once a second of simulated time, so that a session
  /// faster than real time (hitl demo: 46 s in half a second) records it each simulated second.
  void send_status(double now_s, double sim_s, double start_wall_s, const SessionStatus& status);
  /// A STATUSTEXT from the simulator's identity (a fault started or ended): to every client, where
  /// a ground station shows it, and into the recording, so that a recording says what was injected
  /// when. A text longer than STATUSTEXT's 50 characters goes out in chunks (id, chunk_seq), as PX4 sends one.
  void announce(Severity severity, std::string_view text);
  /// Truth (ODOMETRY, estimator MOCAP) to clients and the recording when due at `sim_s`.
  void send_truth_if_due(const sensors::GroundTruth& truth, uint64_t time_usec, double sim_s);
  /// ODOMETRY to the VIO server when due at `sim_s`; true when one was sent (or refused).
  /// The VIO faults (docs/faults.md): vio-loss: the schedule moves on but nothing is sent;
  /// vio-drift/vio-jump move the position, vio-jump counts reset_counter, vio-quality sets quality.
  bool send_vio_if_due(const sensors::GroundTruth& truth, uint64_t time_usec, double sim_s,
                       const faults::ActiveFaults& faults = {});
  // --- the VIO link's faults (link_faults.h) ----------------------------------------------------
  void set_vio_link_faults(const faults::LinkImpairment& impairment, double sim_s) { vio_faults_.set(impairment, sim_s); }
  /// Sends the held ODOMETRY due by `now_s` (the run loop calls it between ticks).
  void release_vio_delayed(double now_s);
  std::optional<double> next_vio_delayed_s() const { return vio_faults_.next_due_s(); }
  const LinkFaults& vio_link_faults() const { return vio_faults_; }
  /// The VIO link's first refused send to each destination, once.
  std::vector<std::string> take_send_errors();

  bool has_clients() const { return clients_.has_value(); }
  std::size_t client_count() const { return clients_ ? clients_->client_count() : 0; }
  uint64_t clients_refused() const { return clients_ ? clients_->stats().refused_datagrams : 0; }
  uint64_t client_frames_dropped() const { return clients_ ? clients_->stats().dropped_frames : 0; }
  uint64_t routed_to_clients() const { return routed_to_clients_; }
  /// ", ODOMETRY to ... at 250 Hz, clients on 127.0.0.1:14600, GCS host:port"
  std::string describe() const;

  static constexpr std::size_t kMaxDatagramsPerDrain = 64;

 private:
  ClientServices(const SessionConfig& config, const mavlink::MessageSet& messages, StackLink& stack, Traffic& traffic,
                 Recording& recording);
  template <class M>
  void broadcast_own(const M& message);
  void send_doctor_status(uint32_t boot_ms, const SessionStatus& status);
  void send_loop_latency(uint32_t boot_ms, double sim_s, const SessionStatus& status);
  /// One ODOMETRY frame onto the VIO link (recorded as it leaves, counted).
  void send_vio_frame(std::span<const uint8_t> frame, bool counted);

  const SessionConfig& config_;
  StackLink& stack_;
  Traffic& traffic_;
  Recording& recording_;
  std::optional<net::ClientPort> clients_;
  mavlink::FrameParser client_parser_;
  router::Router router_;  ///< board <-> clients, the same code path as hitl bridge (no dedup: one path)
  router::LinkId board_link_ = 0, clients_link_ = 0;
  uint64_t routed_to_clients_ = 0;
  mavlink::FrameEncoder own_encoder_;  ///< the session's status and truth to clients
  mavlink::StatusTextChunker statustext_chunker_;
  std::unique_ptr<net::Link> vio_;
  mavlink::FrameEncoder vio_encoder_;  ///< the VIO link's own sequence
  LinkFaults vio_faults_;
  double next_status_wall_s_ = 0;
  double next_latency_sim_s_ = 0;
  double next_vio_s_ = 0;
  uint64_t vio_k_ = 0;
  double next_truth_s_ = 0;
  uint64_t truth_k_ = 0;
  bool warned_full_ = false;
  bool warned_dropped_ = false;
};

}  // namespace hitl::hil
