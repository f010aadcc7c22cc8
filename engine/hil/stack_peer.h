// Which flight stack is on the other end of the HIL link, decided once from the session's
// configuration, and what follows from it. Every part of the session asks this for a capability
// (lockstep, the answers' clock, whether a loss comes back, what to tell the user) and never for
// the flavour: a new flavour (issue 38: a PX4 that hitl starts) is one more case here.
//
//   a board         PX4 in HIL mode (a VOXL2, hitl target): UDP to -i:--hil-port from --local-port,
//                   heard from that address only; lockstep when --lockstep asks; it answers from the
//                   first HIL_SENSOR and may stamp its answers with its own clock; it can restart
//                   and be heard again
//   PX4 SITL        simulator_mavlink (--px4-sitl): PX4 connects to hitl's TCP port (tcpin:4560),
//                   or hitl sends to its UDP port (udp:HOST:PORT); always lockstep on the
//                   HIL_SENSOR's time; silent for its first ~1.1 s; over TCP it never reconnects
//   PX4 that hitl started (--px4 DIR, px4_launch.h): PX4 SITL as instance N, connecting to TCP
//                   127.0.0.1:4560+N; besides, its GCS MAVLink instance (UDP 18570+N) carries the
//                   session's client traffic both ways (commands, the pilot's sticks, PX4's
//                   HEARTBEAT for the mode), as a board's HIL link does
#pragma once

#include <string>
#include <string_view>

#include "base/common/expected.h"
#include "engine/hil/session_config.h"
#include "engine/net/link_spec.h"
#include "engine/net/open_link.h"
#include "engine/px4/px4_instance.h"

namespace hitl::hil {

/// The --px4-sitl value in the link grammar (engine/net/link_spec.h): tcpin:[HOST:]PORT (PX4
/// connects) or udp:HOST:PORT (PX4's UDP simulator port); the spellings before it, tcp:PORT (=
/// tcpin:PORT) and udp:PORT (= udp:TARGET_IP:PORT), too. The Error (input) names the value.
Expected<net::LinkSpec> parse_px4_sitl(std::string_view text, const std::string& target_ip);

/// Whose clock the answers' time_usec is on.
enum class AnswerClock {
  SensorTime,   ///< the HIL_SENSOR's time_usec, echoed (PX4 SITL's lockstep clock)
  OwnOrSensor,  ///< a board's own clock (PX4 in HIL mode), or the echo (hitl target --lockstep)
};

class StackPeer {
 public:
  /// Decided from --px4-sitl (none: a board at -i), or PX4 that this session started as instance
  /// `owned` (--px4: the caller claims the instance, px4_launch.h).
  static Expected<StackPeer> decide(const SessionConfig& config, const std::optional<px4::Px4Instance>& owned = {});

  // --- the link ------------------------------------------------------------------------------
  const net::LinkSpec& link() const { return link_; }
  const net::LinkSettings& link_settings() const { return settings_; }
  /// The stack connects to hitl (tcpin): the session waits for it before the first step.
  bool connects_in() const { return link_.kind == net::LinkSpec::Kind::TcpIn; }
  /// "connected" is the link's (a stream); otherwise it is the answers arriving.
  bool link_tells_connected() const { return link_.stream(); }
  /// A lost stream is closed for good: the session ends on it, not on lockstep's silence rule.
  bool link_tells_loss() const { return link_.stream(); }
  /// The link takes the session's client traffic (commands, a trajectory's sticks) besides HIL
  /// messages; PX4 SITL's TCP simulator link takes HIL messages only.
  bool carries_client_traffic() const { return flavour_ != Flavour::Px4Sitl || !link_.stream(); }
  /// The stack's own MAVLink link beside the HIL link, which then carries the client traffic and
  /// what the stack says (HEARTBEAT, STATUSTEXT, ...): PX4 that hitl started, its GCS instance.
  std::optional<net::LinkSpec> telemetry_link() const;
  const net::LinkSettings& telemetry_link_settings() const { return telemetry_settings_; }
  /// The stack's mode (PX4's HEARTBEAT) reaches the session: a board's on its HIL link, an owned
  /// PX4's on its telemetry link; PX4 SITL's simulator link sends one HEARTBEAT, at connect.
  bool reports_mode() const { return flavour_ != Flavour::Px4Sitl; }
  /// The session started the stack and stops it at the end (px4_launch.h).
  bool owned() const { return flavour_ == Flavour::Px4Owned; }

  // --- time ----------------------------------------------------------------------------------
  /// Every step waits for the answer to its HIL_SENSOR (PX4 SITL always; a board with --lockstep).
  bool lockstep() const { return lockstep_; }
  /// Answers from the first HIL_SENSOR (a board): lockstep waits for that first answer once.
  /// PX4 SITL is silent for its first ~1.1 s: the steps go on until it answers.
  bool answers_first_sensor() const { return flavour_ == Flavour::Board; }
  AnswerClock answer_clock() const { return flavour_ == Flavour::Board ? AnswerClock::OwnOrSensor : AnswerClock::SensorTime; }

  // --- words ---------------------------------------------------------------------------------
  /// "PX4 SITL" / "the board".
  const char* name() const { return flavour_ == Flavour::Board ? "the board" : "PX4 SITL"; }
  /// What to start while the session waits for it to connect (connects_in()).
  std::string start_hint() const;
  /// Why nothing answered the first HIL_SENSORs; `peer` the address, `warning_s` how long it waited.
  std::string no_answer_cause(const std::string& peer, double warning_s) const;
  /// The link was lost for good (link_tells_loss()).
  std::string lost_text() const;

 private:
  enum class Flavour { Board, Px4Sitl, Px4Owned };
  StackPeer(Flavour flavour, bool lockstep, net::LinkSpec link, net::LinkSettings settings)
      : flavour_(flavour), lockstep_(lockstep), link_(std::move(link)), settings_(std::move(settings)) {}

  Flavour flavour_ = Flavour::Board;  ///< asked here only
  std::optional<px4::Px4Instance> instance_;  ///< Px4Owned: the instance hitl started
  net::LinkSettings telemetry_settings_;
  bool lockstep_ = false;
  net::LinkSpec link_;
  net::LinkSettings settings_;
};

}  // namespace hitl::hil
