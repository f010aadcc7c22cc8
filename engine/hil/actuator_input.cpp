#include "engine/hil/actuator_input.h"

#include "base/mavlink/enums.h"

namespace hitl::hil {

bool ActuatorInput::on_message(const mavlink::msg::HilActuatorControls& message, uint8_t sysid, double now_s) {
  if (sysid_ && *sysid_ != sysid) {
    ++counters_.ignored_sysid;
    return false;
  }
  sysid_ = sysid;
  ++counters_.received;
  ++heard_;
  heard_s_ = now_s;
  if (expected_us_) {
    const uint64_t t = message.time_usec, expected = *expected_us_;
    echo_offset_us_ = static_cast<int64_t>(t - expected);
    if (t < expected && expected - t <= kEchoWindow_us && t >= *first_expected_us_) {
      ++counters_.late;  // answers an earlier HIL_SENSOR: already stepped on without it
      last_s_ = now_s;   // the flight stack is alive: no motor timeout
      in_timeout_ = false;
      return false;
    }
    if (t < expected || t >= expected + kStep_us) ++counters_.foreign_clock;
  }
  ++fresh_;
  bool clamped = false;
  for (std::size_t i = 0; i < last_.u.size(); ++i) {
    const auto checked = model::check_motor_command(message.controls[i]);  // the model's rule, once
    clamped = clamped || checked.fix != model::CommandFix::None;
    last_.u[i] = checked.u;
  }
  if (clamped) ++counters_.clamped;
  mode_ = message.mode;
  flags_ = static_cast<uint8_t>(message.flags);
  last_.armed = (message.mode & mavlink::mode_flag::kSafetyArmed) != 0;
  last_s_ = now_s;
  in_timeout_ = false;
  return true;
}

model::MotorCommands ActuatorInput::commands(double now_s) {
  if (timed_out(now_s)) {
    if (!in_timeout_ && last_s_) ++counters_.timeouts;
    in_timeout_ = true;
    return model::MotorCommands{};
  }
  return last_;
}

}  // namespace hitl::hil
