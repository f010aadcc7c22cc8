// HIL_ACTUATOR_CONTROLS from the flight stack -> the motor commands the model flies on.
// controls[0..3] are the four motors in 0..1 (PX4's quad-X order); the armed bit is in `mode`.
// Non-finite or out-of-range controls are clamped and counted; a second sysid is ignored once
// one is locked; no message for the timeout stops the motors.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "engine/mavlink/messages.h"
#include "engine/model/multicopter.h"

namespace hitl::hil {

struct ActuatorCounters {
  uint64_t received = 0;        ///< HIL_ACTUATOR_CONTROLS accepted
  uint64_t clamped = 0;         ///< messages with at least one motor control NaN, inf or outside 0..1
  uint64_t ignored_sysid = 0;   ///< from another system than the one locked onto
  uint64_t timeouts = 0;        ///< times the stream stopped for longer than the timeout
};

class ActuatorInput {
 public:
  explicit ActuatorInput(double timeout_s) : timeout_s_(timeout_s) {}

  /// Takes one message received at `now_s` (a monotonic clock). Returns false when ignored.
  bool on_message(const mavlink::msg::HilActuatorControls& message, uint8_t sysid, double now_s);

  /// The commands to fly on at `now_s`: the latest ones, or stopped (disarmed) after the timeout.
  model::MotorCommands commands(double now_s);

  bool ever_received() const { return last_s_.has_value(); }
  bool timed_out(double now_s) const { return !last_s_ || now_s - *last_s_ > timeout_s_; }
  /// Messages taken since the last call (lockstep asks "did the board answer?").
  uint64_t take_new() {
    const uint64_t n = fresh_;
    fresh_ = 0;
    return n;
  }
  const ActuatorCounters& counters() const { return counters_; }
  const std::array<double, 4>& last_controls() const { return last_.u; }
  bool armed() const { return last_.armed; }
  uint8_t last_flags() const { return flags_; }
  uint8_t last_mode() const { return mode_; }
  std::optional<uint8_t> locked_sysid() const { return sysid_; }

 private:
  double timeout_s_;
  std::optional<double> last_s_;
  std::optional<uint8_t> sysid_;
  model::MotorCommands last_;
  uint8_t flags_ = 0;
  uint8_t mode_ = 0;
  bool in_timeout_ = true;
  uint64_t fresh_ = 0;
  ActuatorCounters counters_;
};

}  // namespace hitl::hil
