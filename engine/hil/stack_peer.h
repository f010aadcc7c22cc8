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
#pragma once

#include <string>
#include <string_view>

#include "base/common/expected.h"
#include "engine/hil/session_config.h"
#include "engine/net/link_spec.h"
#include "engine/net/open_link.h"

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
  /// Decided from --px4-sitl (none: a board at -i).
  static Expected<StackPeer> decide(const SessionConfig& config);

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
  bool carries_client_traffic() const { return !(sitl_ && link_.stream()); }

  // --- time ----------------------------------------------------------------------------------
  /// Every step waits for the answer to its HIL_SENSOR (PX4 SITL always; a board with --lockstep).
  bool lockstep() const { return lockstep_; }
  /// Answers from the first HIL_SENSOR (a board): lockstep waits for that first answer once.
  /// PX4 SITL is silent for its first ~1.1 s: the steps go on until it answers.
  bool answers_first_sensor() const { return !sitl_; }
  AnswerClock answer_clock() const { return sitl_ ? AnswerClock::SensorTime : AnswerClock::OwnOrSensor; }

  // --- words ---------------------------------------------------------------------------------
  /// "PX4 SITL" / "the board".
  const char* name() const { return sitl_ ? "PX4 SITL" : "the board"; }
  /// What to start while the session waits for it to connect (connects_in()).
  std::string start_hint() const;
  /// Why nothing answered the first HIL_SENSORs; `peer` the address, `warning_s` how long it waited.
  std::string no_answer_cause(const std::string& peer, double warning_s) const;
  /// The link was lost for good (link_tells_loss()).
  std::string lost_text() const;

 private:
  StackPeer(bool sitl, bool lockstep, net::LinkSpec link, net::LinkSettings settings)
      : sitl_(sitl), lockstep_(lockstep), link_(std::move(link)), settings_(std::move(settings)) {}

  bool sitl_ = false;  ///< the flavour: asked here only
  bool lockstep_ = false;
  net::LinkSpec link_;
  net::LinkSettings settings_;
};

}  // namespace hitl::hil
