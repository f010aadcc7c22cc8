// `hitl replay FILE.tlog`: sends a recorded session's steps (recorded_session.h) to a board open
// loop, with the recorded timing, or in lockstep one step at a time (each waits for the answer
// stamped with its HIL_SENSOR's time_usec, as hitl sim --lockstep does), and records what the
// board answers. Never prints: progress goes to an observer. docs/replay.md.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/contract/board_ports.h"
#include "engine/replay/recorded_session.h"

namespace hitl::replay {

struct ReplayConfig {
  std::string target_ip = "127.0.0.1";
  uint16_t hil_port = kBoardHilPort;
  uint16_t vio_port = kBoardVioPort;  ///< 0: no ODOMETRY is sent
  std::string bind_address = "0.0.0.0";
  uint16_t local_port = kSimLocalPort;  ///< the simulator's port: a board answers only the first port it heard
  bool lockstep = false;
  double lockstep_timeout_s = 0.5;    ///< a step without its answer by then goes on (counted)
  double give_up_s = 5.0;             ///< nothing at all from the board for this long ends the replay
  std::string record_path;            ///< --record: everything sent and received
};

struct ReplayProgress {
  uint64_t step = 0, steps = 0, answers = 0, fallbacks = 0;
  double sim_time_s = 0;
};

struct ReplayResult {
  uint64_t steps_sent = 0;
  uint64_t frames_sent = 0;
  uint64_t answers = 0;            ///< HIL_ACTUATOR_CONTROLS received
  uint64_t fallbacks = 0;          ///< lockstep: steps whose answer did not come in time
  double wall_time_s = 0;
  bool stopped = false;            ///< `stop` ended it early
  std::vector<ActuatorSample> actuators;  ///< the board's answers, each with its step
};

/// Runs the replay. An Error: the sockets or the record file cannot be opened, a send fails, or the
/// board says nothing for give_up_s.
Expected<ReplayResult> run_replay(const RecordedSession& session, const ReplayConfig& config, const std::atomic<bool>& stop,
                                  const std::function<void(const ReplayProgress&)>& on_progress);

}  // namespace hitl::replay
