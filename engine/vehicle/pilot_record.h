// What the trajectory pilot writes into a recording besides the frames on the wire, so that a
// recording holds everything `hitl report` draws (docs/report.md): as MAV_COMP_ID_PATHPLANNER of the
// flying system (the simulator's id under `hitl sim -t`, the ground station's under `hitl fly
// trajectory`), its own sequence, never sent to anyone: per step of the flown reference a
// POSITION_TARGET_LOCAL_NED (the setpoint, NED in the pose's frame), in TRAJECTORY also a
// NAMED_VALUE_FLOAT "trk_err" (the error the tracking RMS/max are computed from), and each state
// change as a STATUSTEXT ("trajectory: HOLD (trajectory flown)").
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string_view>

#include "base/common/severity.h"
#include "base/contract/session_status.h"
#include "base/mavlink/frame_encoder.h"
#include "engine/mavlink/statustext.h"
#include "engine/vehicle/trajectory.h"

namespace hitl::vehicle {

class PilotRecord {
 public:
  using Sink = std::function<void(std::span<const uint8_t> frame)>;
  PilotRecord(Sink sink, uint8_t sysid, mavlink::Version protocol = mavlink::Version::V2);
  /// The reference flown at `time_ms`, ENU in the pose's frame; the scored error when there is one.
  void setpoint(uint32_t time_ms, const TrajectoryReference& reference, std::optional<double> tracking_error_m);
  void note(Severity severity, std::string_view text);

 private:
  template <class M>
  void record(const M& message);
  Sink sink_;
  mavlink::FrameEncoder encoder_;
  mavlink::StatusTextChunker statustext_chunker_;
};

}  // namespace hitl::vehicle
