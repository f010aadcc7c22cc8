#include "target/core/simulated_battery.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hitl::target {
namespace {

TEST(SimulatedBattery, IsTheSpecsFullPack) {
  const BatteryStatus b = make_simulated_battery(123);
  EXPECT_EQ(b.timestamp_us, 123U);
  EXPECT_TRUE(b.connected);
  EXPECT_FLOAT_EQ(b.voltage_V, 16.8F);
  EXPECT_FLOAT_EQ(b.current_A, 5.0F);
  EXPECT_FLOAT_EQ(b.current_average_A, 5.0F);
  EXPECT_FLOAT_EQ(b.remaining_ratio, 1.0F);
  EXPECT_FLOAT_EQ(b.discharged_mAh, 0.0F);
  EXPECT_FLOAT_EQ(b.scale, 1.0F);
  EXPECT_EQ(b.cell_count, 4);
  EXPECT_FLOAT_EQ(b.voltage_V / b.cell_count, 4.2F);  // full LiPo cells
  EXPECT_EQ(b.id, 1);
  EXPECT_EQ(b.warning, 0);
  EXPECT_TRUE(std::isnan(b.time_remaining_s));
  EXPECT_TRUE(std::isnan(b.temperature_degC));
  EXPECT_EQ(kSimBatteryPeriod_us, 100000U);
}

}  // namespace
}  // namespace hitl::target
