#include "cli/session_dashboard.h"

#include <atomic>
#include <iostream>
#include <thread>

#include "tui/draw.h"
#include "tui/terminal.h"

namespace hitl::cli {

const char* end_reason_name(hil::Session::EndReason r) {
  switch (r) {
    case hil::Session::EndReason::Duration: return "duration";
    case hil::Session::EndReason::Stopped: return "stopped";
    case hil::Session::EndReason::FlightStackGone: return "flight_stack_gone";
    case hil::Session::EndReason::TrajectoryDone: return "trajectory_done";
    case hil::Session::EndReason::TrajectoryFailed: return "trajectory_failed";
  }
  return "?";
}

Expected<hil::Session::EndReason> run_session_with_dashboard(const GlobalOptions& global, const std::string& command,
                                                             hil::Session& session, const hil::SessionConfig& config,
                                                             tui::SimDashboardConfig dashboard_config,
                                                             const std::function<void(tui::SimDashboard*)>& attach) {
  tui::SimDashboard dashboard(session, config, std::move(dashboard_config));
  if (attach) attach(&dashboard);
  std::atomic<bool> stop{false};
  Expected<hil::Session::EndReason> end = Error::failed("not run");
  std::thread loop([&] {
    end = session.run(stop, dashboard);
    dashboard.mark_finished(end ? std::string("the session ended (") + end_reason_name(*end) + ")"
                                : "error: " + end.error().message);
  });
  auto shown = tui::run_dashboard(dashboard, &dashboard);
  stop.store(true);
  loop.join();
  if (attach) attach(nullptr);
  dashboard.shutdown();
  const std::string who = "hitl " + command;
  if (!shown) {
    log_error(command, "--tui: " + shown.error().message);
    return end;
  }
  if (shown->reason == tui::DashboardEnd::Reason::Signal) std::cerr << who << ": stopped by " << shown->detail << '\n';
  if (global.verbosity >= 1)
    log_info(global, tui::format("%s: the dashboard drew %llu frames, %.2f ms each on average, %.2f ms at most", who.c_str(),
                                 static_cast<unsigned long long>(shown->frames), shown->render_ms_mean, shown->render_ms_max));
  return end;
}

}  // namespace hitl::cli
