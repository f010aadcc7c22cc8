// RC_CHANNELS_OVERRIDE -> sticks with PX4's default map (1 roll, 2 pitch, 3 throttle, 4 yaw).
#include "emulator/flight/rc_input.h"

#include <gtest/gtest.h>

namespace hitl::flight {
namespace {

constexpr std::uint16_t kIgnore = 65535;

TEST(RcInput, CentredSticksAndMidThrottle) {
  const StickInput s = sticks_from_rc_override({1500, 1500, 1500, 1500, kIgnore, kIgnore, kIgnore, kIgnore}, 42);
  EXPECT_EQ(s.time_us, 42u);
  EXPECT_DOUBLE_EQ(s.roll, 0.0);
  EXPECT_DOUBLE_EQ(s.pitch, 0.0);
  EXPECT_DOUBLE_EQ(s.yaw, 0.0);
  EXPECT_DOUBLE_EQ(s.throttle, 0.5);
}

TEST(RcInput, ChannelMapAndDirections) {
  const StickInput s = sticks_from_rc_override({2000, 1250, 1000, 1750, 0, 0, 0, 0}, 0);
  EXPECT_DOUBLE_EQ(s.roll, 1.0);       // ch1 high: right
  EXPECT_DOUBLE_EQ(s.pitch, -0.5);     // ch2 low: backward
  EXPECT_DOUBLE_EQ(s.throttle, 0.0);   // ch3 low
  EXPECT_DOUBLE_EQ(s.yaw, 0.5);        // ch4 high: clockwise
}

TEST(RcInput, OutOfRangeIsClamped) {
  const StickInput s = sticks_from_rc_override({900, 2200, 2500, 800, kIgnore, kIgnore, kIgnore, kIgnore}, 0);
  EXPECT_DOUBLE_EQ(s.roll, -1.0);
  EXPECT_DOUBLE_EQ(s.pitch, 1.0);
  EXPECT_DOUBLE_EQ(s.throttle, 1.0);
  EXPECT_DOUBLE_EQ(s.yaw, -1.0);
}

TEST(RcInput, ReleasedOrIgnoredChannelsKeepThePreviousValue) {
  StickInput previous;
  previous.roll = 0.3;
  previous.throttle = 0.7;
  const StickInput s = sticks_from_rc_override({0, 1600, kIgnore, 1500, 0, 0, 0, 0}, 5, previous);
  EXPECT_DOUBLE_EQ(s.roll, 0.3);
  EXPECT_DOUBLE_EQ(s.pitch, 0.2);
  EXPECT_DOUBLE_EQ(s.throttle, 0.7);
}

TEST(RcInput, RoundTrip) {
  StickInput in;
  in.roll = -0.4;
  in.pitch = 0.6;
  in.yaw = 0.2;
  in.throttle = 0.8;
  const StickInput out = sticks_from_rc_override(rc_override_from_sticks(in), 0);
  EXPECT_NEAR(out.roll, in.roll, 1e-3);
  EXPECT_NEAR(out.pitch, in.pitch, 1e-3);
  EXPECT_NEAR(out.yaw, in.yaw, 1e-3);
  EXPECT_NEAR(out.throttle, in.throttle, 1e-3);
}

}  // namespace
}  // namespace hitl::flight
