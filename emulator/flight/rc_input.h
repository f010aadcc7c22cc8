// RC_CHANNELS_OVERRIDE (PWM microseconds, 1000..2000) -> StickInput, with PX4's default channel map
// (RC_MAP_ROLL 1, RC_MAP_PITCH 2, RC_MAP_THROTTLE 3, RC_MAP_YAW 4) and an uncalibrated, unreversed
// radio (RCx_MIN 1000, RCx_TRIM 1500, RCx_MAX 2000, RCx_REV +1):
//   roll  = (ch1 - 1500) / 500     2000 us = full right
//   pitch = (ch2 - 1500) / 500     2000 us = full forward (nose down, fly forward)
//   throttle = (ch3 - 1000) / 1000 1500 us = centre (hold altitude in position mode)
//   yaw   = (ch4 - 1500) / 500     2000 us = full right (clockwise)
// MAVLink: a channel value of 0 releases the channel, UINT16_MAX ignores it; both keep the previous
// stick value here. Values are clamped to their range.
#pragma once

#include <array>
#include <cstdint>

#include "emulator/flight/inputs.h"

namespace hitl::flight {

/// 0-based indices into RC_CHANNELS_OVERRIDE chan1_raw..chan8_raw (PX4 default RC_MAP_*).
struct RcChannelMap {
  int roll = 0;
  int pitch = 1;
  int throttle = 2;
  int yaw = 3;
};

/// Sticks from the first eight override channels; channels that are 0 or UINT16_MAX keep `previous`.
StickInput sticks_from_rc_override(const std::array<std::uint16_t, 8>& channels_us, std::uint64_t time_us,
                                   const StickInput& previous = {}, const RcChannelMap& map = {});

/// The inverse (tests, tools): sticks -> PWM microseconds in the same map (other channels UINT16_MAX).
std::array<std::uint16_t, 8> rc_override_from_sticks(const StickInput& sticks, const RcChannelMap& map = {});

}  // namespace hitl::flight
