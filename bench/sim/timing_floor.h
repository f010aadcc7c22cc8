// sim_timing_bench's floor: the session's system calls and traffic at 250 Hz with no simulator in
// them (timing_floor.cpp says what it does).
#pragma once

#include <cstdint>

namespace hitl::bench {

/// The ports a `hitl sim` session under the bench would use.
struct FloorPorts {
  uint16_t board = 0;    ///< the stand-in board's HIL port (HIL_SENSOR goes there)
  uint16_t sim = 0;      ///< the loop's own port, where the board answers
  uint16_t vio = 0;      ///< the VIO server's port (ODOMETRY)
  uint16_t clients = 0;  ///< the client port a truth client sends to
};

/// Runs the loop for `seconds` (SIGINT ends it at once); returns the process exit code.
/// `sendmmsg_both`: HIL_SENSOR and ODOMETRY leave in one sendmmsg() from one socket, not two sendto().
int run_timing_floor(const FloorPorts& ports, double seconds, bool sendmmsg_both);

}  // namespace hitl::bench
