// What the dashboard's keys ask for, and the interface a source offers to carry it out. Actions
// run off the drawing thread (they wait for ACKs) and report their outcome to the messages panel.
#pragma once

#include <optional>
#include <string>

namespace hitl::tui {

enum class Action {
  Arm,
  Disarm,
  ForceDisarm,     ///< confirmed by the operator: the vehicle is in the air
  Takeoff,
  Land,
  TogglePause,
  ResetHome,
  FlyTrajectory,
  StopTrajectory,  ///< confirmed by the operator
  Shell,           ///< with the command line as argument
  Fault,           ///< with the typed fault as argument: "gps-loss+10" starts one now, "clear [NAME]" ends
};

/// "arm", "force disarm", "pause/resume", ...
const char* to_string(Action action);

class DashboardActions {
 public:
  virtual ~DashboardActions() = default;
  /// Why `action` cannot run here or now (shown in the messages panel), or nullopt when it can.
  virtual std::optional<std::string> refusal(Action action) const = 0;
  /// Starts `action` and returns at once; the outcome goes to the messages panel.
  virtual void perform(Action action, const std::string& argument) = 0;
};

}  // namespace hitl::tui
