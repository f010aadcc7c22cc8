#include "engine/doctor/px4_checks.h"

#include <cmath>
#include <cstdlib>

#include "base/mavlink/enums.h"
#include "engine/doctor/check_catalog.h"
#include "engine/px4/px4_instance.h"

namespace hitl::doctor {
namespace {

std::string instance_ports(int index) {
  const px4::Px4Instance i{index};
  return "TCP " + std::to_string(i.simulator_tcp_port()) + ", GCS UDP " + std::to_string(i.gcs_udp_port()) + ", system id " +
         std::to_string(i.sysid());
}

/// PX4 stores parameters as float32: equal within its precision.
bool same_value(double have, double want) { return std::fabs(have - want) <= 1e-5 * std::max(1.0, std::fabs(want)); }

}  // namespace

std::string px4_sitl_skip_reason(const SessionStatus& session) {
  return "PX4 SITL started by the session (instance " + std::to_string(session.px4_instance.value_or(-1)) +
         "): no VOXL2 board, so nothing of the board's to check";
}

CheckResult px4_build_check(const Px4Findings& f) {
  if (!f.build) return make_result(check::kPx4Build, Verdict::Skip, "no --px4 DIR given");
  if (!*f.build)
    return make_result(check::kPx4Build, Verdict::Fail, f.build->error().message,
                       "build PX4 v1.16.0 SITL: scripts/px4-sitl.sh TREE, then --px4 TREE");
  const px4::Px4Build& b = f.build->value();
  const std::string what = "PX4 " + (b.version.empty() ? std::string("(version not given by the build)") : b.version) +
                           " SITL at " + b.build_dir + (b.lockstep ? " (lockstep)" : " (no lockstep)");
  if (!b.lockstep)
    return make_result(check::kPx4Build, Verdict::Fail, what + ": hitl sim --px4 needs lockstep",
                       "build px4_sitl_default (scripts/px4-sitl.sh TREE), not px4_sitl_nolockstep");
  if (b.version.empty())
    return make_result(check::kPx4Build, Verdict::Warn, what,
                       "rebuild with scripts/px4-sitl.sh TREE (PX4's version comes from its git tag)");
  return make_result(check::kPx4Build, Verdict::Pass, what);
}

CheckResult px4_instance_check(const Px4Findings& f, const SessionStatus& session) {
  if (session_runs_px4(session)) {
    const int n = *session.px4_instance;
    if (n < 0)
      return make_result(check::kPx4Instance, Verdict::Warn,
                         "the session started PX4 but it has not connected yet (its instance is claimed)",
                         "wait, or see PX4's console: FILE.px4.log beside --record, or console.log in its working folder");
    return make_result(check::kPx4Instance, Verdict::Pass, "the session's PX4 holds instance " + std::to_string(n) + " (" +
                                                                instance_ports(n) + ")");
  }
  if (!f.build) return make_result(check::kPx4Instance, Verdict::Skip, "no PX4 session and no --px4 DIR given");
  if (!f.first_free) {
    return make_result(check::kPx4Instance, Verdict::Fail,
                       "none of PX4's instances 0.." + std::to_string(px4::Px4Instance::kMax) + " is free" +
                           (f.busy.empty() ? std::string() : " (instance 0: " + f.busy.front().why + ")"),
                       "stop the PX4 SITL processes that hold them (pgrep -a px4)");
  }
  const std::string takes = "hitl sim --px4 takes instance " + std::to_string(*f.first_free) + " (" + instance_ports(*f.first_free) + ")";
  if (f.busy.empty()) return make_result(check::kPx4Instance, Verdict::Pass, takes);
  std::string why;
  for (const auto& b : f.busy) why += (why.empty() ? "" : "; ") + std::string("instance ") + std::to_string(b.index) + ": " + b.why;
  return make_result(check::kPx4Instance, Verdict::Warn, why + "; " + takes,
                     "nothing to do if those are other sessions' PX4; a PX4 left behind: pgrep -a px4, then kill it");
}

CheckResult px4_connected_check(const Px4Findings& f, const SessionStatus& session, const std::optional<HeartbeatSeen>& heartbeat) {
  if (!session.heard())
    return make_result(check::kPx4Connected, Verdict::Skip,
                       "no session to ask" + std::string(f.build ? ": start one with hitl sim --px4 DIR" : ""));
  if (!session_runs_px4(session))
    return make_result(check::kPx4Connected, Verdict::Skip, "the session flies a board or --px4-sitl, not PX4 it started");
  const int n = *session.px4_instance;
  if (n < 0)
    return make_result(check::kPx4Connected, Verdict::Fail, "the session started PX4, which has not connected to its simulator port",
                       "see PX4's console (FILE.px4.log beside --record, or console.log in its working folder); "
                       "hitl sim ends the session after --px4-timeout");
  const px4::Px4Instance i{n};
  if (!heartbeat || heartbeat->sysid != i.sysid() ||
      heartbeat->autopilot != static_cast<uint8_t>(mavlink::MavAutopilot::Px4))
    return make_result(check::kPx4Connected, Verdict::Fail,
                       "PX4 instance " + std::to_string(n) + " is connected to the simulator but its HEARTBEAT (system id " +
                           std::to_string(i.sysid()) + ") does not come through the session" +
                           (heartbeat ? " (heard system " + std::to_string(heartbeat->sysid) + ")" : ""),
                       "PX4's GCS instance is UDP " + std::to_string(i.gcs_udp_port()) +
                           ": is another program bound to it? (hitl doctor's ports, pgrep -a px4)");
  std::string saw = "PX4 " + f.running_version.value_or("(version not answered)") + ", instance " + std::to_string(n) +
                    ", connected: sensors in, HEARTBEAT through the session";
  if (f.build && *f.build && f.running_version && !f.build->value().version.empty() &&
      *f.running_version != f.build->value().version)
    return make_result(check::kPx4Connected, Verdict::Warn,
                       saw + "; --px4 DIR is " + f.build->value().version + ", not the one running",
                       "point --px4 at the build the session runs (hitl sim prints its folder)");
  return make_result(check::kPx4Connected, Verdict::Pass, saw);
}

CheckResult px4_params_check(const Px4Findings& f, const SessionStatus& session,
                             const Expected<std::vector<vehicle::Param>>& params) {
  if (!session_runs_px4(session) || *session.px4_instance < 0)
    return make_result(check::kPx4Params, Verdict::Skip, "no PX4 connected that the session started");
  if (!params) return make_result(check::kPx4Params, Verdict::Fail, "cannot read PX4's parameters: " + params.error().message,
                                  "hitl params list, to see whether PX4 answers");
  std::string missing, differ, first;
  std::size_t checked = 0;
  for (const auto& want : f.expected) {
    const double want_value = std::strtod(want.value.c_str(), nullptr);
    const vehicle::Param* have = nullptr;
    for (const auto& p : *params)
      if (p.name == want.name) have = &p;
    if (have == nullptr) {
      missing += (missing.empty() ? "" : ", ") + want.name;
      continue;
    }
    ++checked;
    if (!same_value(have->value.as_double(), want_value))
      differ += (differ.empty() ? "" : ", ") + want.name + " " + have->value.to_string() + " (hitl set " + want.value + ")";
    else if (first.empty())
      first = want.name + " " + have->value.to_string();
  }
  if (!missing.empty())
    return make_result(check::kPx4Params, Verdict::Fail, "PX4 has no " + missing,
                       "a PX4 other than v1.16's px4_sitl_default? (hitl sim --px4 refuses an unknown --px4-param)");
  if (!differ.empty())
    return make_result(check::kPx4Params, Verdict::Warn, differ,
                       "hitl set these at PX4's start; a --px4-param of the session that doctor was not given "
                       "(give doctor the same), or changed since: hitl params set NAME VALUE");
  return make_result(check::kPx4Params, Verdict::Pass,
                     "the " + std::to_string(checked) + " parameters hitl gave PX4 are as set (" + first + ", ...)");
}

}  // namespace hitl::doctor
