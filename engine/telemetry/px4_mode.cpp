#include "engine/telemetry/px4_mode.h"

#include <cstdio>

#include "base/mavlink/enums.h"

namespace hitl::telemetry {

std::string px4_mode_name(uint8_t base_mode, uint32_t custom_mode) {
  if ((base_mode & mavlink::mode_flag::kCustomModeEnabled) == 0) return "no custom mode";
  const unsigned main_mode = (custom_mode >> 16) & 0xFFu;
  const unsigned sub_mode = (custom_mode >> 24) & 0xFFu;
  switch (main_mode) {
    case 1: return "Manual";
    case 2: return "Altitude";
    case 3: return sub_mode == 1 ? "Orbit" : "Position";
    case 4:
      switch (sub_mode) {
        case 1: return "Ready";
        case 2: return "Takeoff";
        case 3: return "Hold";
        case 4: return "Mission";
        case 5: return "Return";
        case 6: return "Land";
        case 8: return "Follow Me";
        case 9: return "Precision Land";
        case 10: return "VTOL Takeoff";
        default: break;
      }
      break;
    case 5: return "Acro";
    case 6: return "Offboard";
    case 7: return "Stabilized";
    case 10: return "Termination";
    default: break;
  }
  char text[32];
  std::snprintf(text, sizeof text, "custom 0x%08x", static_cast<unsigned>(custom_mode));
  return text;
}

}  // namespace hitl::telemetry
