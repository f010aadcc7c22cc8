// The autopilot's firmware version from AUTOPILOT_VERSION.flight_sw_version, as PX4 packs it:
// major << 24 | minor << 16 | patch << 8 | FIRMWARE_VERSION_TYPE (0 dev, 64 alpha, 128 beta,
// 192 rc, 255 official).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

/// "v1.16.0", "v1.16.0-dev", "v1.15.2-rc".
std::string format_flight_sw_version(uint32_t flight_sw_version);

/// Asks for AUTOPILOT_VERSION (MAV_CMD_REQUEST_MESSAGE) and waits up to `timeout_s`: the
/// formatted flight_sw_version, or nullopt when it does not come.
std::optional<std::string> request_firmware_version(VehicleLink& link, double timeout_s = 1.5);

}  // namespace hitl::vehicle
