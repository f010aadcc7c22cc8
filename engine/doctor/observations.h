// What doctor hears on its link, folded frame by frame: the autopilot's HEARTBEAT, SYS_STATUS,
// ESTIMATOR_STATUS and STATUSTEXT, and a running session's own status (engine/hil/session_config.h:
// HEARTBEAT and NAMED_VALUE_FLOAT/INT "sim_*" from the simulator's system id, once a second).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/mavlink/frame.h"
#include "engine/mavlink/statustext.h"
#include "engine/telemetry/vehicle_telemetry.h"

namespace hitl::doctor {

struct HeartbeatSeen {
  uint8_t sysid = 0, compid = 0;
  uint8_t autopilot = 0, type = 0, base_mode = 0, system_status = 0;
  uint32_t custom_mode = 0;
  uint64_t count = 0;
  double first_s = 0, last_s = 0;  ///< monotonic
  bool armed() const;
};

struct SysStatusSeen {
  uint32_t present = 0, enabled = 0, health = 0;
};

using EstimatorStatusSeen = telemetry::EstimatorStatusValues;  // decoded once: estimator_status_from()

/// A running session's status (each value the latest; nullopt before it was heard).
struct SessionStatus {
  std::optional<uint8_t> sysid;         ///< who sends "sim_rtf"
  std::optional<uint8_t> system_status; ///< its HEARTBEAT: STANDBY while paused
  std::optional<double> rtf;            ///< recent real-time factor
  std::optional<double> speed;          ///< the requested --speed (0: as fast as possible)
  std::optional<bool> paused;
  std::optional<bool> lockstep;
  std::optional<double> actuator_hz;    ///< HIL_ACTUATOR_CONTROLS received, wall-clock Hz
  std::optional<int32_t> actuator_flags;  ///< -1: none received yet
  std::optional<int32_t> actuator_armed;  ///< 0/1; -1: none received yet
  std::optional<int32_t> loop_latency_p99_us;  ///< "sim_lat99"; -1: no answer yet
  std::optional<int32_t> px4_instance;  ///< "sim_px4": the PX4 the session started (-1: not connected yet)
  /// "sim_late" (late ticks so far) as first and last heard, with their times.
  struct LateSample {
    double t_s = 0;
    int32_t late = 0;
  };
  std::optional<LateSample> first_late, last_late;
  uint64_t reports = 0;                 ///< "sim_rtf" values heard
  bool heard() const { return reports > 0; }
};

struct Observations {
  std::optional<HeartbeatSeen> heartbeat;      ///< the autopilot's
  std::optional<SysStatusSeen> sys_status;
  std::optional<EstimatorStatusSeen> estimator;
  uint64_t estimator_reports = 0;
  std::vector<std::string> statustext;         ///< in arrival order (the last 50), chunks joined
  SessionStatus session;
};

class ObservationTracker {
 public:
  /// A frame from the autopilot (`sysid` the link's target system).
  void on_autopilot_frame(const mavlink::Frame& frame, double now_s);
  /// A frame from any other system (the session's simulator, other clients).
  void on_other_frame(const mavlink::Frame& frame, double now_s);
  /// What was seen; a status text still waiting for its next chunk is counted as it is.
  const Observations& observations();

 private:
  void add_statustext(std::string text);
  Observations seen_;
  mavlink::StatusTextAssembler statustexts_;
};

}  // namespace hitl::doctor
