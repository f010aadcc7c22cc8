// The dashboard's entry point, the same for every command: a source gives the model ten times a
// second, the keys go to the actions, the frame is redrawn. Drawing happens on the calling
// thread and never waits on a session, a socket or an action.
//
//   hitl sim --tui      SimDashboard (sim_dashboard.h): session + vehicle telemetry + actions
//   hitl inspect --tui  InspectDashboard (inspect_dashboard.h): traffic stats, STATUSTEXT, no actions
//   hitl bridge --tui   a source over the bridge's link stats plus the same vehicle telemetry
#pragma once

#include <optional>
#include <string>

#include "base/common/expected.h"
#include "tui/actions.h"
#include "tui/dashboard_model.h"

namespace hitl::tui {

class DashboardSource {
 public:
  virtual ~DashboardSource() = default;
  /// The model to draw now; must not block (copies of snapshots only).
  virtual DashboardModel collect() = 0;
  /// Why the dashboard should close (the session ended), or nullopt while it runs.
  virtual std::optional<std::string> finished() = 0;
  /// A line for the messages panel from the dashboard itself (a refusal, a cancelled question).
  virtual void note(Severity severity, const std::string& text) = 0;
};

struct DashboardOptions {
  double refresh_hz = 10;
};

struct DashboardEnd {
  enum class Reason { Quit, Signal, SourceFinished };
  Reason reason = Reason::Quit;
  std::string detail;           ///< the signal's name or the source's reason
  double render_ms_mean = 0;    ///< what drawing a frame cost (composition and flush)
  double render_ms_max = 0;
  uint64_t frames = 0;
};

/// Runs until `q`, a SIGINT/SIGTERM/SIGHUP, or the source finishing; the terminal is restored on
/// every way out. An Error when the terminal cannot be used (then nothing was drawn).
Expected<DashboardEnd> run_dashboard(DashboardSource& source, DashboardActions* actions, const DashboardOptions& options = {});

}  // namespace hitl::tui
