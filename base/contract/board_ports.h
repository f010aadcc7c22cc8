// The HITL port table (DESIGN.md §4), once: the board's UDP ports, the host's fixed ports towards
// them, the session's client port and the adb relay's TCP port. A PX4 MAVLink instance keeps the
// first sender it heard until it restarts, which is why the host's local ports are fixed too.
#pragma once

#include <cstdint>

namespace hitl {

inline constexpr uint16_t kBoardHilPort = 14560;       ///< the board's primary (HIL) MAVLink instance
inline constexpr uint16_t kBoardVioPort = 14570;       ///< voxl-hitl-vio-server's ODOMETRY listener
inline constexpr uint16_t kBoardGcsPort = 14558;       ///< the board's tertiary (GCS forwarding) instance
inline constexpr uint16_t kSimLocalPort = 14561;       ///< the simulator sends HIL traffic from here
inline constexpr uint16_t kDirectLocalPort = 14562;    ///< direct commands and inspect --connect talk from here
inline constexpr uint16_t kSessionClientPort = 14600;  ///< local clients of a session or a bridge (127.0.0.1)
inline constexpr uint16_t kAdbRelayTcpPort = 14590;    ///< hitl-adb-relay on the board (`adb forward tcp:L tcp:14590`)

}  // namespace hitl
