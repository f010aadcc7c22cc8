// The battery the apps processor reports during HIL (spec, MavlinkReceiver): a full 4S pack,
// 16.8 V (4 x 4.2 V), 5.0 A, 100 %, published at 10 Hz. Constants defined here only.
#pragma once

#include <cstdint>

#include "base/contract/data_rates.h"
#include "target/core/px4_topics.h"

namespace hitl::target {

inline constexpr float kSimBatteryVoltage_V = 16.8F;
inline constexpr float kSimBatteryCurrent_A = 5.0F;
inline constexpr float kSimBatteryRemaining_ratio = 1.0F;
inline constexpr uint8_t kSimBatteryCellCount = 4;
inline constexpr uint8_t kSimBatteryId = 1;  ///< battery_status ids are 1-based
using ::hitl::kSimBatteryPeriod_us;  // base/contract/data_rates.h

/// The simulated battery's battery_status at `now_us`: connected, no warning, nothing discharged,
/// scale 1, time remaining and temperature unknown (NaN).
BatteryStatus make_simulated_battery(uint64_t now_us);

}  // namespace hitl::target
