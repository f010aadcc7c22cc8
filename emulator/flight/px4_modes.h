// PX4's mode numbers as MAVLink carries them (src/modules/commander/px4_custom_mode.h):
//   HEARTBEAT.custom_mode = main_mode << 16 | sub_mode << 24
//   main: MANUAL 1, ALTCTL 2, POSCTL 3, AUTO 4, ACRO 5, OFFBOARD 6, STABILIZED 7
//   AUTO sub: READY 1, TAKEOFF 2, LOITER 3, MISSION 4, RTL 5, LAND 6
// Stabilized = STABILIZED (0x00070000), Position = POSCTL (0x00030000), Hold = AUTO.LOITER (0x03040000), Takeoff = AUTO.TAKEOFF
// (0x02040000), Land = AUTO.LAND (0x06040000).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace hitl::flight {

namespace px4_main_mode {
inline constexpr std::uint8_t kManual = 1, kAltctl = 2, kPosctl = 3, kAuto = 4, kAcro = 5, kOffboard = 6,
                              kStabilized = 7;
}
namespace px4_auto_sub_mode {
inline constexpr std::uint8_t kReady = 1, kTakeoff = 2, kLoiter = 3, kMission = 4, kRtl = 5, kLand = 6;
}
/// MAV_MODE_FLAG bits.
namespace mav_mode_flag {
inline constexpr std::uint8_t kCustomModeEnabled = 1, kTestEnabled = 2, kAutoEnabled = 4, kGuidedEnabled = 8,
                              kStabilizeEnabled = 16, kHilEnabled = 32, kManualInputEnabled = 64,
                              kSafetyArmed = 128;
}

enum class FlightMode { Position, Hold, Takeoff, Land, Stabilized };

/// MAV_LANDED_STATE.
enum class LandedState : std::uint8_t { Undefined = 0, OnGround = 1, InAir = 2, Takeoff = 3, Landing = 4 };

std::uint32_t px4_custom_mode(FlightMode mode);
/// The mode a custom_mode word asks for; nullopt for modes the flight core does not fly.
std::optional<FlightMode> flight_mode_from_px4(std::uint32_t custom_mode);
/// HEARTBEAT.base_mode as PX4 fills it (custom mode enabled, mode-class bits, armed).
std::uint8_t mav_base_mode(FlightMode mode, bool armed);
/// PX4's names: "Position", "Hold", "Takeoff", "Land", "Stabilized".
std::string to_string(FlightMode mode);
std::string to_string(LandedState state);

}  // namespace hitl::flight
