// A hitl sim recording (--record FILE.tlog) read for replay: the steps the session sent the board
// (each HIL_SENSOR with the frames that followed it to the board in the same step: HIL_GPS, the
// pilot's commands, HEARTBEAT; and its VIO ODOMETRY), and the board's HIL_ACTUATOR_CONTROLS, each
// with the step it came in. What went to or came from clients (the session's status, ground
// truth, the board's telemetry) is left out. docs/replay.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/common/expected.h"

namespace hitl::replay {

/// A recording larger than this is refused (about 50 minutes of a session at 250 Hz).
inline constexpr uint64_t kMaxRecordingBytes = 256ull << 20;

enum class Destination { Hil, Vio };

struct OutgoingFrame {
  Destination to = Destination::Hil;
  std::vector<uint8_t> bytes;  ///< one whole MAVLink frame
};

struct RecordedStep {
  uint64_t sensor_time_usec = 0;  ///< the HIL_SENSOR's time_usec: the session's simulated time
  uint64_t t_unix_us = 0;         ///< when the recording wrote it (wall clock): the replay's timing
  /// In recorded order: a client's frames forwarded at the step's start (recorded after the last
  /// step's ODOMETRY), the HIL_SENSOR, what followed it to the board (HIL_GPS, the pilot's
  /// commands, HEARTBEAT), and its VIO ODOMETRY.
  std::vector<OutgoingFrame> frames;
};

/// One HIL_ACTUATOR_CONTROLS: its stamp, the step it arrived in (the last HIL_SENSOR sent before
/// it; -1 before the first), and its four motor controls (PX4's quad-X order).
struct ActuatorSample {
  uint64_t time_usec = 0;
  int64_t step = -1;
  std::array<float, 4> controls{};
  uint8_t mode = 0;
};

struct RecordedSession {
  std::vector<RecordedStep> steps;
  std::vector<ActuatorSample> actuators;
  uint8_t simulator_sysid = 0;
  uint64_t frames = 0;         ///< frames in the file
  uint64_t vio_frames = 0;     ///< ODOMETRY to voxl-hitl-vio-server
  uint64_t other_frames = 0;   ///< to the board beside HIL_SENSOR and ODOMETRY (HIL_GPS, commands, HEARTBEAT)
  double duration_s() const;   ///< simulated time from the first step to the last
};

/// Reads `path`. An Error (ErrorKind::Input) naming the file: missing or unreadable, larger than
/// `max_bytes`, not a .tlog, cut off or corrupt, or holding no HIL_SENSOR (not a hitl sim recording).
Expected<RecordedSession> load_recording(const std::string& path, uint64_t max_bytes = kMaxRecordingBytes);

}  // namespace hitl::replay
