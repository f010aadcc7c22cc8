#include "target/core/simulated_battery.h"

#include <limits>

namespace hitl::target {

BatteryStatus make_simulated_battery(uint64_t now_us) {
  BatteryStatus b;
  b.timestamp_us = now_us;
  b.connected = true;
  b.voltage_V = kSimBatteryVoltage_V;
  b.current_A = kSimBatteryCurrent_A;
  b.current_average_A = kSimBatteryCurrent_A;
  b.discharged_mAh = 0.0F;
  b.remaining_ratio = kSimBatteryRemaining_ratio;
  b.scale = 1.0F;
  b.time_remaining_s = std::numeric_limits<float>::quiet_NaN();
  b.temperature_degC = std::numeric_limits<float>::quiet_NaN();
  b.cell_count = kSimBatteryCellCount;
  b.source = 0;
  b.id = kSimBatteryId;
  b.warning = 0;
  return b;
}

}  // namespace hitl::target
