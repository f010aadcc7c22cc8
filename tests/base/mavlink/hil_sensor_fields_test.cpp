// HIL_SENSOR.fields_updated, one header for host, board and PX4 (base/mavlink/hil_sensor_fields.h):
// the bits are MAVLink's HIL_SENSOR_UPDATED_FLAGS and the groups PX4's.
#include "base/mavlink/hil_sensor_fields.h"

#include <gtest/gtest.h>

namespace hitl::mavlink::hil_sensor {
namespace {

TEST(HilSensorFields, GroupsAreMavlinksAndPx4s) {
  EXPECT_EQ(kAccel, 0x007U);
  EXPECT_EQ(kGyro, 0x038U);
  EXPECT_EQ(kMag, 0x1C0U);
  EXPECT_EQ(kBaro, 0x1A00U);
  EXPECT_EQ(kDiffPressure, 0x400U);
  EXPECT_EQ(kReset, 0x80000000U);
}

TEST(HilSensorFields, HasGroupNeedsEveryBit) {
  EXPECT_TRUE(has_group(0x1FFF, kBaro));
  EXPECT_TRUE(has_group(0x1A00, kBaro));
  EXPECT_FALSE(has_group(0x0200, kBaro));  // abs_pressure alone
  EXPECT_FALSE(has_group(0x0A00, kBaro));  // without temperature
  EXPECT_TRUE(has_group(0x007, kAccel));
  EXPECT_FALSE(has_group(0x003, kAccel));
}

}  // namespace
}  // namespace hitl::mavlink::hil_sensor
