#include "engine/doctor/simulator_checks.h"

#include <cstdio>
#include <string>

#include "base/contract/board_ports.h"
#include "base/contract/data_rates.h"
#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "engine/doctor/check_catalog.h"

namespace hitl::doctor {
namespace {

const char* kNoSession = "no session";

}  // namespace

CheckResult session_check(const SessionStatus& s, uint16_t session_port, std::optional<bool> sensors_arriving) {
  const std::string where = "127.0.0.1:" + std::to_string(session_port);
  if (s.heard())
    return make_result(check::kSession, Verdict::Pass,
                       "hitl sim (system " + std::to_string(*s.sysid) + ") on " + where +
                           (s.lockstep ? (*s.lockstep ? ", lockstep" : ", free-running") : "") +
                           (s.speed ? (*s.speed > 0 ? ", --speed " + fixed(*s.speed, 1) : ", as fast as possible") : ""));
  const std::string fix = "hitl sim -i BOARD_IP (with --clients PORT: hitl doctor --session-port PORT)";
  if (sensors_arriving.value_or(false))
    return make_result(check::kSession, Verdict::Warn,
                       "no hitl sim session on " + where + ", but the board receives sensor data: another simulator drives it",
                       fix);
  return make_result(check::kSession, Verdict::Fail,
                     "no hitl sim session on " + where + (sensors_arriving ? " and the board receives no sensor data" : ""), fix);
}

CheckResult paused_check(const SessionStatus& s) {
  if (!s.heard()) return make_result(check::kPaused, Verdict::Skip, kNoSession);
  const bool standby = s.system_status && *s.system_status == static_cast<uint8_t>(mavlink::MavState::Standby);
  if (s.paused.value_or(false) || standby)
    return make_result(check::kPaused, Verdict::Fail, "the session is paused: the model holds and no sensor data is sent",
                       "resume it: the p key in hitl sim --tui");
  return make_result(check::kPaused, Verdict::Pass, "running");
}

CheckResult real_time_check(const SessionStatus& s) {
  if (!s.heard() || !s.rtf) return make_result(check::kRealTime, Verdict::Skip, kNoSession);
  const double rtf = *s.rtf;
  const std::string saw = "real-time factor " + fixed(rtf, 2);
  if (!s.speed) return make_result(check::kRealTime, Verdict::Pass, saw);
  if (!(*s.speed > 0)) return make_result(check::kRealTime, Verdict::Pass, saw + " (as fast as possible)");
  const double ratio = rtf / *s.speed;
  const std::string against = saw + " against --speed " + fixed(*s.speed, 1);
  if (ratio >= 0.9 && ratio <= 1.1) return make_result(check::kRealTime, Verdict::Pass, against);
  const std::string fix = "this host cannot hold the pace: close other programs, try hitl sim --realtime, or lower --speed";
  if (ratio < 0.8 && !s.lockstep.value_or(false))
    return make_result(check::kRealTime, Verdict::Fail, against + ": the board's clock runs on, so its sensors come too slowly", fix);
  return make_result(check::kRealTime, Verdict::Warn, against + (s.lockstep.value_or(false) ? " (lockstep: the board waits)" : ""), fix);
}

CheckResult late_ticks_check(const SessionStatus& s) {
  if (!s.heard()) return make_result(check::kLateTicks, Verdict::Skip, kNoSession);
  if (!s.first_late || !s.last_late || !(s.last_late->t_s > s.first_late->t_s))
    return make_result(check::kLateTicks, Verdict::Skip, "the session reported late ticks only once");
  const double dt_s = s.last_late->t_s - s.first_late->t_s;
  const int64_t late = static_cast<int64_t>(s.last_late->late) - s.first_late->late;
  const double ticks = dt_s * s.rtf.value_or(1.0) / hitl::kStepPeriod_s;
  const std::string saw = std::to_string(late) + " late of ~" + fixed(ticks, 0) + " ticks in " + fixed(dt_s, 1) + " s (" +
                          std::to_string(s.last_late->late) + " since the start)";
  if (late <= 0) return make_result(check::kLateTicks, Verdict::Pass, saw);
  const std::string fix = "a busy host: close other programs, or run hitl sim --realtime (SCHED_FIFO when permitted)";
  if (!s.lockstep.value_or(false) && ticks > 0 && static_cast<double>(late) / ticks > 0.05)
    return make_result(check::kLateTicks, Verdict::Fail, saw + ": the board sees gaps in the sensor stream", fix);
  return make_result(check::kLateTicks, Verdict::Warn, saw, fix);
}

CheckResult loop_latency_check(const SessionStatus& s) {
  if (!s.heard()) return make_result(check::kLoopLatency, Verdict::Skip, kNoSession);
  if (!s.loop_latency_p99_us || *s.loop_latency_p99_us < 0)
    return make_result(check::kLoopLatency, Verdict::Skip, "no HIL_ACTUATOR_CONTROLS has answered a HIL_SENSOR yet");
  const double p99_ms = *s.loop_latency_p99_us / 1000.0;
  const bool lockstep = s.lockstep.value_or(false);
  const double step_ms = hitl::kStepPeriod_s * 1000.0;
  const double floor_ms = lockstep ? 0.0 : static_cast<double>(hitl::kActuatorStreamPeriod_us) / 1000.0 + step_ms;
  const double limit_ms = floor_ms + step_ms;
  const std::string saw = "p99 " + fixed(p99_ms, 2) + " ms from a HIL_SENSOR to " +
                          (lockstep ? "its answer (lockstep, one step " + fixed(step_ms, 0) + " ms)"
                                    : "the next HIL_ACTUATOR_CONTROLS (limit " + fixed(limit_ms, 0) +
                                          " ms: the board's stream period and the session's tick, plus one step)");
  if (p99_ms <= limit_ms) return make_result(check::kLoopLatency, Verdict::Pass, saw);
  return make_result(check::kLoopLatency, Verdict::Warn, saw + ": the board answers later than a step, so it flies on old sensors",
                     "a slow link (USB: hitl doctor's link checks, try another port or cable) or a busy board; "
                     "hitl sim --json's loop_latency has the histogram");
}

}  // namespace hitl::doctor
