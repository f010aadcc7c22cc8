// The HEARTBEAT hitl's ground-station-like commands send so that a PX4 instance streams to them.
#pragma once

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"

namespace hitl::mavlink {

/// MAV_TYPE_GCS, MAV_AUTOPILOT_INVALID (no vehicle), active.
inline msg::Heartbeat gcs_heartbeat() {
  msg::Heartbeat hb;
  hb.type = static_cast<uint8_t>(MavType::Gcs);
  hb.autopilot = static_cast<uint8_t>(MavAutopilot::Invalid);
  hb.system_status = static_cast<uint8_t>(MavState::Active);
  hb.mavlink_version = kMavlinkVersion;
  return hb;
}

}  // namespace hitl::mavlink
