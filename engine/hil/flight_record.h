// What the trajectory pilot (-t) writes into --record besides the frames on the wire, so that a
// recording holds everything `hitl report` draws (docs/report.md): from the simulator's system id
// and MAV_COMP_ID_PATHPLANNER (its own sequence, never sent to anyone), per step of the flown
// reference a POSITION_TARGET_LOCAL_NED (the setpoint, world NED, time_boot_ms = simulated ms), in
// TRAJECTORY also a NAMED_VALUE_FLOAT "trk_err" (the error the tracking RMS/max are computed from),
// and each state change as a STATUSTEXT ("trajectory: HOLD (trajectory flown)").
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "base/common/severity.h"
#include "base/contract/session_status.h"
#include "base/mavlink/frame_encoder.h"
#include "engine/hil/recording.h"
#include "engine/vehicle/trajectory.h"

namespace hitl::hil {

class FlightRecord {
 public:
  FlightRecord(Recording& recording, uint8_t sysid, mavlink::Version protocol);
  /// The reference flown at `time_us` (simulated), world ENU; the scored error when there is one.
  void setpoint(uint64_t time_us, const vehicle::TrajectoryReference& reference_world, std::optional<double> tracking_error_m);
  void note(Severity severity, std::string_view text);

 private:
  template <class M>
  void record(const M& message);
  Recording& recording_;
  mavlink::FrameEncoder encoder_;
};

}  // namespace hitl::hil
