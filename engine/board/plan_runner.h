// Runs a plan (board_plan.h) step by step: each step said before it runs, each board command's exit
// code checked. The first failure stops the run with what failed, the board's output, the steps
// already done that changed the board, and the commands that undo them.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/board/board_plan.h"
#include "engine/board/board_shell.h"

namespace hitl::board {

/// The host's side of a plan: what WaitForPx4 and HitlParams do (px4_link.h gives the real ones).
struct HostActions {
  std::function<Status()> wait_for_px4;
  /// Sets what differs; the names it set. An Error when a parameter could not be set.
  std::function<Expected<std::vector<std::string>>()> hitl_params;
};

struct RunReport {
  bool ok = true;
  std::size_t steps_done = 0;
  std::optional<std::size_t> failed_step;
  std::string failed_action;             ///< the action's text
  std::string error;                     ///< why: exit code and message
  std::string board_output;              ///< what the board printed (the command's, or the diagnose command's)
  std::vector<std::string> changed;      ///< names of the steps done (and the failed one) that change the board
  std::vector<std::string> undo;         ///< board commands undoing them, in the order to run them
  std::vector<std::string> params_set;   ///< HitlParams: what it set
  std::vector<std::string> params_restart;  ///< of those, what needed PX4 restarted
};

struct RunCallbacks {
  std::function<void(std::size_t step)> step_started;       ///< before each step
  std::function<void(const std::string& line)> said;       ///< results worth a line (parameters set, restart)
};

RunReport run_plan(const BoardPlan& plan, BoardShell& shell, const HostActions& host, const RunCallbacks& callbacks);

}  // namespace hitl::board
