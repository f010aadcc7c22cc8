// One decoded frame as the line `hitl inspect --show` prints: format_message's names for enum and
// bitmask values, and PX4's flight mode in HEARTBEAT.custom_mode as the dashboard names it
// (telemetry::px4_mode_name): "HEARTBEAT custom_mode=Position type=QUADROTOR autopilot=PX4 ...".
#pragma once

#include <string>

#include "base/mavlink/frame.h"

namespace hitl::inspect {

std::string frame_text(const mavlink::Frame& frame);

}  // namespace hitl::inspect
