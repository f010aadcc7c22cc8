// Every HEARTBEAT hitl sends, built in one place: one builder and a named one per role hitl plays
// (a ground station, the simulator, the bridge as an onboard component, the emulated PX4 board).
#pragma once

#include <cstdint>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"

namespace hitl::mavlink {

/// HEARTBEAT with mavlink_version set; base_mode and custom_mode 0 unless given.
inline msg::Heartbeat heartbeat(MavType type, MavAutopilot autopilot, MavState status, uint8_t base_mode = 0,
                                uint32_t custom_mode = 0) {
  msg::Heartbeat hb;
  hb.type = static_cast<uint8_t>(type);
  hb.autopilot = static_cast<uint8_t>(autopilot);
  hb.base_mode = base_mode;
  hb.custom_mode = custom_mode;
  hb.system_status = static_cast<uint8_t>(status);
  hb.mavlink_version = kMavlinkVersion;
  return hb;
}

/// What hitl's ground-station-like commands send so that a PX4 instance streams to them:
/// MAV_TYPE_GCS, MAV_AUTOPILOT_INVALID (no vehicle), active.
inline msg::Heartbeat gcs_heartbeat() { return heartbeat(MavType::Gcs, MavAutopilot::Invalid, MavState::Active); }

/// The simulator's (hitl sim, to the flight stack and its clients): MAV_TYPE_GENERIC, no autopilot;
/// STANDBY while paused.
inline msg::Heartbeat simulator_heartbeat(MavState status = MavState::Active) {
  return heartbeat(MavType::Generic, MavAutopilot::Invalid, status);
}

/// The bridge's: an onboard component, not a ground station (PX4's GCS-loss logic must not count it).
inline msg::Heartbeat onboard_heartbeat() { return heartbeat(MavType::Onboard, MavAutopilot::Invalid, MavState::Active); }

/// A PX4 quadrotor's (hitl target): the flight stack's base_mode flags and custom mode; ACTIVE when
/// armed, else STANDBY.
inline msg::Heartbeat px4_quadrotor_heartbeat(uint8_t base_mode, uint32_t custom_mode, bool armed) {
  return heartbeat(MavType::Quadrotor, MavAutopilot::Px4, armed ? MavState::Active : MavState::Standby, base_mode,
                   custom_mode);
}

}  // namespace hitl::mavlink
