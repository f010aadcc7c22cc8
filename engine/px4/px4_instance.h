// PX4 SITL's instance N and what it occupies on this machine (PX4 v1.16's px4 -i N): the simulator
// port it connects to (TCP 4560+N), its GCS MAVLink instance (UDP 18570+N), its offboard/API
// instance (UDP 14580+N), its system id (N+1), and /tmp/px4_lock-N, which a running PX4 holds
// with a POSIX record lock. One place names these numbers.
#pragma once

#include <cstdint>
#include <string>

namespace hitl::px4 {

struct Px4Instance {
  int index = 0;
  static constexpr int kMax = 63;  ///< the instances hitl tries: 0..kMax

  uint16_t simulator_tcp_port() const { return static_cast<uint16_t>(4560 + index); }
  uint16_t gcs_udp_port() const { return static_cast<uint16_t>(18570 + index); }
  uint16_t offboard_udp_port() const { return static_cast<uint16_t>(14580 + index); }
  uint8_t sysid() const { return static_cast<uint8_t>(index + 1); }
  std::string lock_file() const { return "/tmp/px4_lock-" + std::to_string(index); }
};

/// Why instance `i` cannot be used now ("a PX4 runs as instance 2 (/tmp/px4_lock-2 is locked)",
/// "UDP 18572 (its GCS port) is in use"), or "" when it is free. The simulator port is not checked
/// here: the caller claims it by listening on it, which settles a race between two hitl sessions.
std::string px4_instance_busy(const Px4Instance& i);

}  // namespace hitl::px4
