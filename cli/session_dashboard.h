// --tui for a simulator session (`hitl sim --tui`, `hitl demo --tui`): the session runs on its own
// thread, the sim dashboard (docs/tui.md) on this one; either ending ends both.
#pragma once

#include <functional>
#include <string>

#include "cli/common_options.h"
#include "engine/hil/session.h"
#include "tui/sim_dashboard.h"

namespace hitl::cli {

/// The session's end as JSON and the summary say it: "duration", "stopped", "trajectory_done", ...
const char* end_reason_name(hil::Session::EndReason reason);

/// Runs `session` under the dashboard. `attach` (when given) is called with the dashboard before
/// the session starts and with nullptr once it has ended, for other event sources (the demo's
/// board) to write into its messages panel instead of over the screen.
Expected<hil::Session::EndReason> run_session_with_dashboard(
    const GlobalOptions& global, const std::string& command, hil::Session& session, const hil::SessionConfig& config,
    tui::SimDashboardConfig dashboard_config, const std::function<void(tui::SimDashboard*)>& attach = {});

}  // namespace hitl::cli
