// PX4's flight mode from HEARTBEAT, in the names QGroundControl shows. PX4 carries it in
// custom_mode as main_mode << 16 | sub_mode << 24 (src/modules/commander/px4_custom_mode.h).
#pragma once

#include <cstdint>
#include <string>

namespace hitl::telemetry {

/// "Position", "Hold", "Takeoff", "Land", ...; "custom 0x00050000" for a word PX4 does not define,
/// "no custom mode" when base_mode lacks MAV_MODE_FLAG_CUSTOM_MODE_ENABLED.
std::string px4_mode_name(uint8_t base_mode, uint32_t custom_mode);

}  // namespace hitl::telemetry
