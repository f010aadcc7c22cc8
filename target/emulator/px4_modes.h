// PX4's flight modes as they travel in HEARTBEAT.custom_mode (px4_custom_mode.h): the main mode
// in bits 16..23, the sub mode in bits 24..31. base_mode carries MAV_MODE_FLAG bits.
#pragma once

#include <cstdint>

#include "engine/mavlink/enums.h"

namespace hitl::target {

enum class Px4MainMode : uint8_t { Manual = 1, Altctl = 2, Posctl = 3, Auto = 4, Acro = 5, Offboard = 6, Stabilized = 7 };
enum class Px4AutoMode : uint8_t { None = 0, Ready = 1, Takeoff = 2, Loiter = 3, Mission = 4, Rtl = 5, Land = 6 };

struct Px4Mode {
  Px4MainMode main = Px4MainMode::Posctl;
  Px4AutoMode sub = Px4AutoMode::None;
  bool operator==(const Px4Mode&) const = default;
};

inline uint32_t custom_mode(Px4Mode mode) {
  return (static_cast<uint32_t>(mode.main) << 16) | (static_cast<uint32_t>(mode.sub) << 24);
}

inline Px4Mode mode_from_custom(uint32_t custom) {
  return {static_cast<Px4MainMode>((custom >> 16) & 0xFF), static_cast<Px4AutoMode>((custom >> 24) & 0xFF)};
}

/// HEARTBEAT.base_mode as PX4's commander fills it (HIL bit with SYS_HITL, armed bit when armed).
inline uint8_t base_mode(Px4Mode mode, bool armed, bool hil) {
  namespace f = mavlink::mode_flag;
  uint8_t b = f::kCustomModeEnabled | f::kStabilizeEnabled;
  switch (mode.main) {
    case Px4MainMode::Manual:
    case Px4MainMode::Acro:
      b = f::kCustomModeEnabled | f::kManualInputEnabled;
      break;
    case Px4MainMode::Altctl:
    case Px4MainMode::Stabilized: b |= f::kManualInputEnabled; break;
    case Px4MainMode::Posctl: b |= f::kManualInputEnabled | f::kGuidedEnabled; break;
    case Px4MainMode::Auto: b |= f::kAutoEnabled | f::kGuidedEnabled; break;
    case Px4MainMode::Offboard: b |= f::kGuidedEnabled; break;
  }
  if (hil) b |= f::kHilEnabled;
  if (armed) b |= f::kSafetyArmed;
  return b;
}

inline const char* mode_name(Px4Mode mode) {
  switch (mode.main) {
    case Px4MainMode::Manual: return "Manual";
    case Px4MainMode::Altctl: return "Altitude";
    case Px4MainMode::Posctl: return "Position";
    case Px4MainMode::Acro: return "Acro";
    case Px4MainMode::Offboard: return "Offboard";
    case Px4MainMode::Stabilized: return "Stabilized";
    case Px4MainMode::Auto:
      switch (mode.sub) {
        case Px4AutoMode::Takeoff: return "Takeoff";
        case Px4AutoMode::Loiter: return "Hold";
        case Px4AutoMode::Land: return "Land";
        case Px4AutoMode::Mission: return "Mission";
        case Px4AutoMode::Rtl: return "Return";
        default: return "Auto";
      }
  }
  return "?";
}

}  // namespace hitl::target
