// The board's sensor path (spec "Verify": `qshell dsp_hitl status` showing incrementing counters;
// Troubleshooting "Verify dsp_hitl status shows increasing counters"): two reads of the status
// text, their counters' rates against the spec's Data Flow Rates. Pure.
#pragma once

#include <optional>
#include <string>

#include "base/common/expected.h"
#include "engine/doctor/check_result.h"
#include "engine/telemetry/dsp_hitl_meter.h"

namespace hitl::doctor {

/// One read of `qshell dsp_hitl status`: the shell's text (or why there was none) and when it came.
struct DspHitlRead {
  Expected<std::string> text = Error::failed("not read");
  double t_s = 0;
};

/// dsp-hitl: running, every counter increasing between the reads, at the spec's rates times
/// `pace` (the board's clock against the wall: the session's real-time factor in lockstep, else 1).
/// `simulator_sending`: whether a session is known to send sensor data (shapes the fix).
CheckResult dsp_hitl_check(const DspHitlRead& first, const DspHitlRead& second, double pace,
                           std::optional<bool> simulator_sending);

/// Whether the two reads show hil_sensor_imu arriving (used by the session check).
bool dsp_hitl_counting(const DspHitlRead& first, const DspHitlRead& second);

}  // namespace hitl::doctor
