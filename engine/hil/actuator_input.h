// HIL_ACTUATOR_CONTROLS from the flight stack -> the motor commands the model flies on.
// controls[0..3] are the four motors in 0..1 (PX4's quad-X order); the armed bit is in `mode`.
// Non-finite or out-of-range controls are clamped and counted; a second sysid is ignored once
// one is locked; no message for the timeout stops the motors.
//
// Lockstep: each answer answers one HIL_SENSOR. PX4 SITL stamps HIL_ACTUATOR_CONTROLS.time_usec
// with its lockstep clock, which is the time_usec of the last HIL_SENSOR it took, and `hitl target
// --lockstep` echoes it the same way. After expect_answer_to(T) (T: the HIL_SENSOR just sent), an
// answer stamped in [T, T + one step) answers it; one stamped up to kEchoWindow_us before T answers
// an earlier HIL_SENSOR (one this session sent): it is late (a second answer, or one that missed its
// step), counted and ignored (neither its controls nor a lockstep step). A stamp outside both (0, or
// far ahead) is on the flight stack's own clock (a stack that does not echo): it counts as an
// answer, as every answer did before.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "base/contract/data_rates.h"
#include "base/mavlink/messages.h"
#include "engine/model/multicopter.h"

namespace hitl::hil {

struct ActuatorCounters {
  uint64_t received = 0;        ///< HIL_ACTUATOR_CONTROLS accepted
  uint64_t clamped = 0;         ///< messages with at least one motor control NaN, inf or outside 0..1
  uint64_t ignored_sysid = 0;   ///< from another system than the one locked onto
  uint64_t timeouts = 0;        ///< times the stream stopped for longer than the timeout
  uint64_t late = 0;            ///< lockstep: answers to an earlier HIL_SENSOR (by time_usec), ignored
  uint64_t foreign_clock = 0;   ///< lockstep: answers whose time_usec is not near any HIL_SENSOR sent
};

class ActuatorInput {
 public:
  static constexpr uint64_t kEchoWindow_us = 1000000;  ///< how far back an echo is taken as late
  static constexpr uint64_t kStep_us = kHilImuPublishPeriod_us;  ///< an echo this far past T still answers T

  explicit ActuatorInput(double timeout_s) : timeout_s_(timeout_s) {}

  /// Lockstep: the HIL_SENSOR whose answer the next step waits for (its time_usec).
  void expect_answer_to(uint64_t time_usec) {
    if (!first_expected_us_) first_expected_us_ = time_usec;
    expected_us_ = time_usec;
  }

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
  /// Messages from the flight stack since the last call, late ones included (is it alive?).
  uint64_t take_heard() {
    const uint64_t n = heard_;
    heard_ = 0;
    return n;
  }
  /// When the last message from the flight stack came (late ones included), on on_message's clock.
  std::optional<double> last_heard_s() const { return heard_s_; }
  /// The last answer's time_usec minus the HIL_SENSOR time it was expected to echo (lockstep), us.
  int64_t last_echo_offset_us() const { return echo_offset_us_; }
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
  uint64_t heard_ = 0;
  std::optional<double> heard_s_;
  std::optional<uint64_t> expected_us_;
  std::optional<uint64_t> first_expected_us_;  ///< stamps before it were never sent (e.g. 0: no echo)
  int64_t echo_offset_us_ = 0;
  ActuatorCounters counters_;
};

}  // namespace hitl::hil
