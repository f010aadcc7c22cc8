// Values of the MAVLink enums hitl uses by name (common.xml / minimal.xml).
#pragma once

#include <cstdint>

namespace hitl::mavlink {

enum class MavType : uint8_t { Generic = 0, Quadrotor = 2, Gcs = 6, Onboard = 18 };
enum class MavAutopilot : uint8_t { Generic = 0, Px4 = 12, Invalid = 8 };
enum class MavState : uint8_t { Uninit = 0, Boot = 1, Calibrating = 2, Standby = 3, Active = 4, Critical = 5, Emergency = 6, Poweroff = 7 };

/// MAV_MODE_FLAG bits of HEARTBEAT.base_mode (and HIL_ACTUATOR_CONTROLS.mode).
namespace mode_flag {
inline constexpr uint8_t kCustomModeEnabled = 1;
inline constexpr uint8_t kTestEnabled = 2;
inline constexpr uint8_t kAutoEnabled = 4;
inline constexpr uint8_t kGuidedEnabled = 8;
inline constexpr uint8_t kStabilizeEnabled = 16;
inline constexpr uint8_t kHilEnabled = 32;
inline constexpr uint8_t kManualInputEnabled = 64;
inline constexpr uint8_t kSafetyArmed = 128;
}  // namespace mode_flag

inline constexpr uint8_t kMavlinkVersion = 3;  ///< HEARTBEAT.mavlink_version

/// Component ids hitl uses for itself.
inline constexpr uint8_t kCompIdMissionPlanner = 190;  ///< MAV_COMP_ID_MISSIONPLANNER: what GCS tools use
inline constexpr uint8_t kGcsSystemId = 255;           ///< the system id ground stations use

}  // namespace hitl::mavlink
