// The session's side of the flight stack: the link StackPeer (stack_peer.h) names, opened by
// net::open_link (the board over UDP, heard only from the target's address, or PX4 SITL's
// simulator link, PX4 connecting over TCP). It owns the net::Link, the HIL
// link's encoder and parser, the actuator input the answers feed, and lockstep: waiting for the
// answer to each HIL_SENSOR, stepping on after a timeout, giving up on a stack silent for
// kLockstepGiveUp_s, and saying when the answers run on another clock (docs/sim.md "Time").
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "base/common/expected.h"
#include "engine/hil/actuator_input.h"
#include "engine/hil/link_faults.h"
#include "engine/hil/pause_clock.h"
#include "engine/hil/recording.h"
#include "engine/hil/session_config.h"
#include "engine/hil/session_events.h"
#include "engine/hil/stack_peer.h"
#include "engine/hil/traffic.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "engine/net/busy_poll.h"
#include "engine/net/link.h"

namespace hitl::hil {

/// Messages the session itself exchanges with the flight stack; never routed to or from clients.
bool is_hil_message(uint32_t msgid);

struct LockstepCounters {
  uint64_t waits = 0;
  uint64_t fallbacks = 0;
};

class StackLink {
 public:
  /// Any frame from the flight stack other than the actuator answers' bookkeeping (they come too).
  using FrameHandler = std::function<void(const mavlink::Frame&, double now_s)>;

  /// Opens the link `peer` names (the board's UDP link, or listens for PX4 SITL); a port in use or
  /// a bad address is an Error.
  static Expected<std::unique_ptr<StackLink>> open(const SessionConfig& config, StackPeer peer, const mavlink::MessageSet& messages,
                                                   Traffic& traffic, Recording& recording, const PauseClock& clock);

  /// A stack that connects in (StackPeer::connects_in()): waits for it (saying how, and every 10 s
  /// how long); false when stopped; `give_up`'s Error (asked every 200 ms: an owned PX4 that exited
  /// or did not connect in time) ends the wait. True at once for any other.
  Expected<bool> wait_until_connected(const std::atomic<bool>& stop, EventSink& events,
                                      const std::function<std::optional<Error>()>& give_up = {});

  // --- sending: queued into one datagram (or one TCP write) per step, sent by flush() ---------
  template <class M>
  void send(const M& message) {
    mavlink::FrameBuffer buf;
    if (const std::size_t n = encoder_.encode(message, buf)) queue({buf.data(), n}, M::kId);
  }
  /// A frame from elsewhere (a client, the trajectory pilot) to the flight stack: on the HIL link,
  /// or on the stack's telemetry link when it has one (StackPeer::telemetry_link()).
  void forward(std::span<const uint8_t> bytes);
  void flush();
  // --- the HIL link's faults (link_faults.h) ---------------------------------------------------
  void set_link_faults(const faults::LinkImpairment& impairment, double sim_s) { link_faults_.set(impairment, sim_s); }
  /// Sends the held datagrams due by `now_s` (the run loop calls it between ticks).
  void release_delayed(double now_s);
  std::optional<double> next_delayed_s() const { return link_faults_.next_due_s(); }
  const LinkFaults& link_faults() const { return link_faults_; }
  /// Each destination's first refused send, in words, once.
  std::vector<std::string> take_send_errors() { return link_->take_send_errors(); }

  // --- receiving -------------------------------------------------------------------------------
  /// Reads what arrived (at most kMaxDatagramsPerDrain datagrams on each link): actuator answers
  /// into actuators(), every frame (also the telemetry link's) to `on_frame`.
  void drain(double now_s, const FrameHandler& on_frame);

  // --- lockstep ------------------------------------------------------------------------------
  bool lockstep() const { return peer_.lockstep(); }
  /// Waits for the answer to the HIL_SENSOR just sent, calling `drain_all` as data arrives.
  void lockstep_wait(EventSink& events, const std::function<void()>& drain_all);
  /// Lockstep against a stack silent for kLockstepGiveUp_s: true (said once) when the session should end.
  bool lockstep_dead(EventSink& events);
  /// Answers on another clock than this session's, said once.
  void check_clock_ahead(EventSink& events);
  /// Nothing back within no_answer_warning_s of the first HIL_SENSOR: said once, with the causes.
  void check_answered(EventSink& events);
  void on_hil_sensor_sent(double wall_s);

  /// A stream to the stack went away (PX4 SITL never reconnects): the session ends.
  bool gone() const { return link_->closed(); }
  /// The stack is there: connected (a stream), or answering (a datagram link).
  bool connected() const { return peer_.link_tells_connected() ? link_->connected() : actuators_.ever_received(); }
  const StackPeer& peer() const { return peer_; }
  ActuatorInput& actuators() { return actuators_; }
  const ActuatorInput& actuators() const { return actuators_; }
  const net::Link& link() const { return *link_; }
  /// The stack's telemetry link (PX4 that hitl started: its GCS instance), or null.
  const net::Link* telemetry_link() const { return telemetry_.get(); }
  const mavlink::ParserStats& parser_stats() const { return parser_.stats(); }
  const LockstepCounters& lockstep_counters() const { return lockstep_counters_; }
  uint64_t routed_to_board() const { return routed_to_board_; }
  /// "HIL_SENSOR/HIL_GPS to 192.168.101.2:14560 from 0.0.0.0:14561" / "serving PX4 SITL on TCP ..."
  std::string describe() const;

  static constexpr std::size_t kMaxDatagramsPerDrain = 256;

 private:
  StackLink(const SessionConfig& config, StackPeer peer, std::unique_ptr<net::Link> link, std::unique_ptr<net::Link> telemetry,
            const mavlink::MessageSet& messages, Traffic& traffic, Recording& recording, const PauseClock& clock);
  /// The telemetry link's frames out, with a HEARTBEAT once a second so that the stack learns
  /// where to send (PX4's UDP MAVLink answers the address it last heard).
  void flush_telemetry();
  void queue_telemetry(std::span<const uint8_t> bytes);
  void queue(std::span<const uint8_t> bytes, std::optional<uint32_t> counted_id);
  /// Sends what the link holds as one datagram and counts its messages (batch_).
  void send_batch();
  std::string no_answer_text() const;
  std::string peer_text() const;

  const SessionConfig& config_;
  StackPeer peer_;
  std::unique_ptr<net::Link> link_;
  mavlink::FrameEncoder encoder_;  ///< the HIL link's sequence
  mavlink::FrameParser parser_;
  std::unique_ptr<net::Link> telemetry_;    ///< StackPeer::telemetry_link(), or null
  mavlink::FrameParser telemetry_parser_;
  double next_telemetry_heartbeat_s_ = 0;
  Traffic& traffic_;
  Recording& recording_;
  const PauseClock& clock_;
  ActuatorInput actuators_;
  LinkFaults link_faults_;
  std::map<uint32_t, uint64_t> batch_;  ///< messages in what flush() sends: counted as sent once it is
  LockstepCounters lockstep_counters_;
  net::AdaptiveBusyPoll busy_poll_;  ///< lockstep: a moment's polling for the answer before sleeping
  uint64_t routed_to_board_ = 0;
  bool stalled_ = false;  ///< a wait ran out: step on without waiting until the stack is heard again
  bool warned_lockstep_ = false;
  bool waited_first_ = false;  ///< lockstep with a board: the first HIL_SENSOR's answer was waited for
  bool warned_clock_ahead_ = false;
  bool warned_no_answer_ = false;
  double first_sensor_wall_s_ = -1;
};

}  // namespace hitl::hil
