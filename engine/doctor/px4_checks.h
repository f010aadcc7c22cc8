// PX4 SITL that hitl starts (hitl sim --px4 DIR, docs/sim.md): the build, the instance it takes or
// holds, whether that PX4 is connected to the session, and whether its parameters are those hitl
// gave it. Decisions on what doctor found (Px4Findings). Pure.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/doctor/check_result.h"
#include "engine/doctor/observations.h"
#include "engine/px4/px4_build.h"
#include "engine/px4/px4_process.h"
#include "engine/vehicle/params_file.h"

namespace hitl::doctor {

/// An instance hitl sim --px4 could not take, and why (px4::px4_instance_busy's words).
struct BusyInstance {
  int index = 0;
  std::string why;
};

/// What the PX4 checks decide on.
struct Px4Findings {
  std::optional<Expected<px4::Px4Build>> build;  ///< --px4 DIR, found or what is missing; nullopt without --px4
  std::vector<BusyInstance> busy;                ///< the instances before the first free one, in order
  std::optional<int> first_free;                 ///< the instance hitl sim --px4 would take now
  std::optional<std::string> running_version;    ///< AUTOPILOT_VERSION of the session's PX4 ("v1.16.0")
  std::vector<px4::Px4Param> expected;           ///< what hitl gives PX4: the x500's, then doctor's --px4-param
};

/// True when the session on the link started PX4 itself (it says sim_px4).
inline bool session_runs_px4(const SessionStatus& s) { return s.px4_instance.has_value(); }

/// px4-build: with --px4 DIR, a PX4 SITL build with its version and lockstep (a px4_sitl_nolockstep
/// build cannot be flown by --px4).
CheckResult px4_build_check(const Px4Findings& f);
/// px4-instance: the instance the session's PX4 holds, or the first that hitl sim --px4 would take
/// (warn when earlier ones are busy, fail when none of 0..63 is free).
CheckResult px4_instance_check(const Px4Findings& f, const SessionStatus& session);
/// px4-connected: the session's PX4 connected to its simulator port and heard on the link (its
/// HEARTBEAT from system id N+1), and the version it runs against --px4 DIR's.
CheckResult px4_connected_check(const Px4Findings& f, const SessionStatus& session, const std::optional<HeartbeatSeen>& heartbeat);
/// px4-params: each parameter hitl gave PX4 (f.expected) as PX4 has it now (the download, or why
/// there is none).
CheckResult px4_params_check(const Px4Findings& f, const SessionStatus& session,
                             const Expected<std::vector<vehicle::Param>>& params);

/// Why a board-only check (dsp_hitl, the board's HITL parameters, its VIO server and ports) is
/// skipped against PX4 SITL that the session started.
std::string px4_sitl_skip_reason(const SessionStatus& session);

}  // namespace hitl::doctor
