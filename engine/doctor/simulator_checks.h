// The simulator (spec Troubleshooting "Verify Gazebo is running and not paused"): a hitl sim session
// on the client port, not paused, keeping its pace, without late ticks. From the session's status
// (observations.h). Pure.
#pragma once

#include <cstdint>
#include <optional>

#include "engine/doctor/check_result.h"
#include "engine/doctor/observations.h"

namespace hitl::doctor {

/// session: one answers on `session_port`. Without one, `sensors_arriving` (dsp_hitl counting)
/// tells "another simulator feeds the board" (warn) from "nothing does" (fail).
CheckResult session_check(const SessionStatus& s, uint16_t session_port, std::optional<bool> sensors_arriving);
CheckResult paused_check(const SessionStatus& s);
/// real-time: the recent real-time factor against the requested --speed. Falling short fails only
/// outside lockstep, where the board runs on its own clock and starves.
CheckResult real_time_check(const SessionStatus& s);
/// late-ticks: ticks that began over a period late between the first and last report, against the
/// ticks in that time (250 per simulated second).
CheckResult late_ticks_check(const SessionStatus& s);
/// loop-latency: the session's p99 from a HIL_SENSOR sent to the HIL_ACTUATOR_CONTROLS that
/// answers it (engine/hil/loop_latency.h). Lockstep: warn above one step. Outside lockstep the
/// answer is the next message of the board's own stream, taken at the session's next tick, so
/// those two periods are the floor: warn above one step beyond them.
CheckResult loop_latency_check(const SessionStatus& s);

}  // namespace hitl::doctor
