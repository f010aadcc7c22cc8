// The board's fields_updated constants must agree with the host's (engine/mavlink): one fact,
// two headers that may not include each other, checked here.
#include "target/core/hil_sensor_fields.h"

#include <gtest/gtest.h>

#include "engine/mavlink/hil_sensor_fields.h"

namespace hitl::target {
namespace {

namespace host = hitl::mavlink::hil_sensor;
namespace board = hitl::target::hil_sensor;

TEST(HilSensorFields, GroupsAreMavlinksAndPx4s) {
  EXPECT_EQ(board::kAccel, 0x007U);
  EXPECT_EQ(board::kGyro, 0x038U);
  EXPECT_EQ(board::kMag, 0x1C0U);
  EXPECT_EQ(board::kBaro, 0x1A00U);
  EXPECT_EQ(board::kDiffPressure, 0x400U);
}

TEST(HilSensorFields, BoardAgreesWithHost) {
  EXPECT_EQ(board::kAccel, host::kAccel);
  EXPECT_EQ(board::kGyro, host::kGyro);
  EXPECT_EQ(board::kMag, host::kMag);
  EXPECT_EQ(board::kBaro, host::kBaro);
  EXPECT_EQ(board::kAbsPressure, host::kAbsPressure);
  EXPECT_EQ(board::kDiffPressure, host::kDiffPressure);
  EXPECT_EQ(board::kPressureAlt, host::kPressureAlt);
  EXPECT_EQ(board::kTemperature, host::kTemperature);
}

TEST(HilSensorFields, HasGroupNeedsEveryBit) {
  EXPECT_TRUE(board::has_group(0x1FFF, board::kBaro));
  EXPECT_TRUE(board::has_group(0x1A00, board::kBaro));
  EXPECT_FALSE(board::has_group(0x0200, board::kBaro));  // abs_pressure alone
  EXPECT_FALSE(board::has_group(0x0A00, board::kBaro));  // without temperature
  EXPECT_TRUE(board::has_group(0x007, board::kAccel));
  EXPECT_FALSE(board::has_group(0x003, board::kAccel));
}

}  // namespace
}  // namespace hitl::target
