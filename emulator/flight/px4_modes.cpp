#include "emulator/flight/px4_modes.h"

namespace hitl::flight {
namespace {
std::uint32_t word(std::uint8_t main_mode, std::uint8_t sub_mode) {
  return (static_cast<std::uint32_t>(main_mode) << 16) | (static_cast<std::uint32_t>(sub_mode) << 24);
}
}  // namespace

std::uint32_t px4_custom_mode(FlightMode mode) {
  switch (mode) {
    case FlightMode::Position: return word(px4_main_mode::kPosctl, 0);
    case FlightMode::Hold: return word(px4_main_mode::kAuto, px4_auto_sub_mode::kLoiter);
    case FlightMode::Takeoff: return word(px4_main_mode::kAuto, px4_auto_sub_mode::kTakeoff);
    case FlightMode::Land: return word(px4_main_mode::kAuto, px4_auto_sub_mode::kLand);
    case FlightMode::Stabilized: return word(px4_main_mode::kStabilized, 0);
  }
  return 0;
}

std::optional<FlightMode> flight_mode_from_px4(std::uint32_t custom_mode) {
  const auto main_mode = static_cast<std::uint8_t>((custom_mode >> 16) & 0xFF);
  const auto sub_mode = static_cast<std::uint8_t>((custom_mode >> 24) & 0xFF);
  if (main_mode == px4_main_mode::kPosctl) return FlightMode::Position;
  if (main_mode == px4_main_mode::kStabilized) return FlightMode::Stabilized;
  if (main_mode != px4_main_mode::kAuto) return std::nullopt;
  switch (sub_mode) {
    case px4_auto_sub_mode::kTakeoff: return FlightMode::Takeoff;
    case px4_auto_sub_mode::kLoiter: return FlightMode::Hold;
    case px4_auto_sub_mode::kLand: return FlightMode::Land;
    default: return std::nullopt;
  }
}

std::uint8_t mav_base_mode(FlightMode mode, bool armed) {
  using namespace mav_mode_flag;
  std::uint8_t m = kCustomModeEnabled | kStabilizeEnabled;
  if (mode == FlightMode::Stabilized) m |= kManualInputEnabled;
  else m |= kGuidedEnabled | (mode == FlightMode::Position ? kManualInputEnabled : kAutoEnabled);
  if (armed) m |= kSafetyArmed;
  return m;
}

std::string to_string(FlightMode mode) {
  switch (mode) {
    case FlightMode::Position: return "Position";
    case FlightMode::Hold: return "Hold";
    case FlightMode::Takeoff: return "Takeoff";
    case FlightMode::Land: return "Land";
    case FlightMode::Stabilized: return "Stabilized";
  }
  return "Unknown";
}

std::string to_string(LandedState state) {
  switch (state) {
    case LandedState::Undefined: return "undefined";
    case LandedState::OnGround: return "on ground";
    case LandedState::InAir: return "in air";
    case LandedState::Takeoff: return "taking off";
    case LandedState::Landing: return "landing";
  }
  return "unknown";
}

}  // namespace hitl::flight
