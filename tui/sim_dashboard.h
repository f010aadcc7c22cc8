// `hitl sim --tui`: the session's snapshots (data paths, truth, rotors, link), the vehicle's
// telemetry and the board's dsp_hitl counters read through the session's own client port
// (BoardClients), and the keys' actions: arm/disarm/takeoff/land and `s` through those clients,
// pause/resume and reset on the session, `f` flies the trajectory in-process (vehicle::fly_trajectory,
// the same flight as `hitl fly trajectory`) through the client port.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "engine/hil/session.h"
#include "engine/vehicle/trajectory.h"
#include "engine/vehicle/trajectory_worker.h"
#include "tui/board_clients.h"
#include "tui/dashboard.h"
#include "tui/graph_history.h"
#include "tui/message_log.h"

namespace hitl::tui {

struct SimDashboardConfig {
  std::string title = "hitl sim";  ///< the header's name (`hitl demo` for the demo)
  std::string no_trajectory_hint = "start hitl sim --tui with -t FILE.json";  ///< what `f` says without a file
  std::string trajectory_file;  ///< -t FILE, named in the messages
  std::optional<vehicle::Trajectory> trajectory;  ///< what `f` flies, read from trajectory_file (none: `f` says how to give one)
  vehicle::StickMode trajectory_mode = vehicle::StickMode::Velocity;  ///< --trajectory-mode
};

class SimDashboard : public DashboardSource, public DashboardActions, public hil::Session::Observer {
 public:
  /// Starts the client-port threads (none with --clients 0: the vehicle panels then say why).
  SimDashboard(hil::Session& session, const hil::SessionConfig& config, SimDashboardConfig dashboard);
  ~SimDashboard() override;

  // DashboardSource
  DashboardModel collect() override;
  std::optional<std::string> finished() override;
  void note(Severity severity, const std::string& text) override { log_.add_outcome(severity, text); }
  // DashboardActions
  std::optional<std::string> refusal(Action action) const override;
  void perform(Action action, const std::string& argument) override;
  // hil::Session::Observer (called on the session's thread)
  void on_event(const hil::SessionEvent& event) override;

  /// The session's run ended: the dashboard closes with `why`.
  void mark_finished(const std::string& why);
  /// Stops the client threads and a trajectory in flight (before the session's sockets close).
  void shutdown();

 private:
  hil::Session& session_;
  hil::SessionConfig config_;
  SimDashboardConfig dashboard_;
  MessageLog log_;
  GraphHistory graphs_;  ///< the last 60 s for the graphs (collect() is the only user)
  std::atomic<double> tracking_error_m_{0};  ///< the flying trajectory's latest, for the graphs
  BoardClients board_;
  vehicle::TrajectoryWorker trajectory_;
  mutable std::mutex finished_mutex_;
  std::optional<std::string> finished_;
};

}  // namespace hitl::tui
