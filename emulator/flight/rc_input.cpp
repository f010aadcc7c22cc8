#include "emulator/flight/rc_input.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hitl::flight {
namespace {

constexpr std::uint16_t kRelease = 0;
constexpr std::uint16_t kIgnore = std::numeric_limits<std::uint16_t>::max();

bool usable(std::uint16_t us) { return us != kRelease && us != kIgnore; }
double centred(std::uint16_t us) { return std::clamp((static_cast<double>(us) - 1500.0) / 500.0, -1.0, 1.0); }
double from_min(std::uint16_t us) { return std::clamp((static_cast<double>(us) - 1000.0) / 1000.0, 0.0, 1.0); }
std::uint16_t pwm(double value_1000_2000) {
  return static_cast<std::uint16_t>(std::lround(std::clamp(value_1000_2000, 1000.0, 2000.0)));
}

}  // namespace

StickInput sticks_from_rc_override(const std::array<std::uint16_t, 8>& channels_us, std::uint64_t time_us,
                                   const StickInput& previous, const RcChannelMap& map) {
  StickInput s = previous;
  s.time_us = time_us;
  const auto ch = [&](int index) { return channels_us[static_cast<std::size_t>(index)]; };
  if (usable(ch(map.roll))) s.roll = centred(ch(map.roll));
  if (usable(ch(map.pitch))) s.pitch = centred(ch(map.pitch));
  if (usable(ch(map.yaw))) s.yaw = centred(ch(map.yaw));
  if (usable(ch(map.throttle))) s.throttle = from_min(ch(map.throttle));
  return s;
}

std::array<std::uint16_t, 8> rc_override_from_sticks(const StickInput& sticks, const RcChannelMap& map) {
  std::array<std::uint16_t, 8> out;
  out.fill(kIgnore);
  out[static_cast<std::size_t>(map.roll)] = pwm(1500.0 + 500.0 * sticks.roll);
  out[static_cast<std::size_t>(map.pitch)] = pwm(1500.0 + 500.0 * sticks.pitch);
  out[static_cast<std::size_t>(map.yaw)] = pwm(1500.0 + 500.0 * sticks.yaw);
  out[static_cast<std::size_t>(map.throttle)] = pwm(1000.0 + 1000.0 * sticks.throttle);
  return out;
}

}  // namespace hitl::flight
