// HIL_ACTUATOR_CONTROLS as the VOXL2 sends it (the spec's "Check msg.flags = 0x0F"): what the
// emulated board sends, the emulator's flight core fills in and hitl doctor's actuator-flags check
// expects, once.
#pragma once

#include <cstdint>

namespace hitl {

/// HIL_ACTUATOR_CONTROLS.flags the VOXL2 sends for a quad (motors 0-3 as a bitmask), per the spec;
/// upstream PX4 sends 0.
inline constexpr uint64_t kVoxl2ActuatorFlags = 0x0F;

}  // namespace hitl
