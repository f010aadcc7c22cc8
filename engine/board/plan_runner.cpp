#include "engine/board/plan_runner.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

#include "engine/board/restart_params.h"

namespace hitl::board {
namespace {

/// Generated text pushed from a host temporary file, removed again.
Status push_text(BoardShell& shell, const std::string& content, const std::string& remote) {
  char path[] = "/tmp/hitl-board-XXXXXX";
  const int fd = ::mkstemp(path);
  if (fd < 0) return Error::unavailable("cannot create a temporary file in /tmp for " + remote);
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  ::close(fd);
  Status pushed = written == content.size() ? shell.push(path, remote) : Status(Error::unavailable(std::string("cannot write ") + path));
  ::unlink(path);
  return pushed;
}

std::string both(const net::ProgramOutput& out) {
  std::string text = out.out;
  if (!out.err.empty()) text += (text.empty() || text.back() == '\n' ? "" : "\n") + out.err;
  return text;
}

}  // namespace

RunReport run_plan(const BoardPlan& plan, BoardShell& shell, const HostActions& host, const RunCallbacks& cb) {
  RunReport report;
  auto fail = [&](std::size_t index, const BoardAction& action, std::string error, std::string output) {
    report.ok = false;
    report.failed_step = index;
    report.failed_action = action.text();
    report.error = std::move(error);
    report.board_output = std::move(output);
    if (!action.diagnose.empty()) {
      auto diag = shell.run(action.diagnose);
      if (diag) report.board_output += (report.board_output.empty() ? "" : "\n") + ("$ " + action.diagnose + "\n") + both(*diag);
    }
  };
  for (std::size_t i = 0; i < plan.steps.size() && report.ok; ++i) {
    const BoardStep& step = plan.steps[i];
    if (cb.step_started) cb.step_started(i);
    bool restart_needed = false;
    for (const auto& action : step.actions) {
      if (action.only_after_restart_params && !restart_needed) continue;
      if (action.kind == ActionKind::Shell) {
        auto out = shell.run(action.command);
        if (!out) {
          fail(i, action, out.error().message, "");
          break;
        }
        if (out->exit_code != 0) {
          fail(i, action, "exit " + std::to_string(out->exit_code), both(*out));
          break;
        }
      } else if (action.kind == ActionKind::Push) {
        Status pushed = action.local_path.empty() ? push_text(shell, action.content, action.remote_path)
                                                  : shell.push(action.local_path, action.remote_path);
        if (!pushed) {
          fail(i, action, pushed.error().message, "");
          break;
        }
      } else if (action.kind == ActionKind::WaitForPx4) {
        Status ready = host.wait_for_px4 ? host.wait_for_px4() : Status(Error::failed("no link to PX4 to wait on"));
        if (!ready) {
          fail(i, action, ready.error().message, "");
          break;
        }
        if (cb.said) cb.said("PX4 is up and dsp_hitl is running");
      } else if (action.kind == ActionKind::HitlParams) {
        auto set = host.hitl_params ? host.hitl_params() : Expected<std::vector<std::string>>(Error::failed("no link to PX4"));
        if (!set) {
          fail(i, action, set.error().message, "");
          break;
        }
        report.params_set = *set;
        report.params_restart = restart_params(*set);
        restart_needed = !report.params_restart.empty();
        if (cb.said) {
          std::string names;
          for (const auto& n : *set) names += (names.empty() ? "" : ", ") + n;
          cb.said(set->empty() ? "the HITL parameters are all as the spec sets them" : "set " + names);
          if (restart_needed) {
            std::string r;
            for (const auto& n : report.params_restart) r += (r.empty() ? "" : ", ") + n;
            cb.said(r + " take" + (report.params_restart.size() == 1 ? "s" : "") + " effect only when PX4 starts again: restarting PX4");
          }
        }
      }
    }
    if (step.changes_board) report.changed.push_back(step.name);
    if (report.ok) ++report.steps_done;
  }
  // The undo list: the steps run (the failed one included: it may have half happened), last first.
  const std::size_t last = report.failed_step ? *report.failed_step + 1 : report.steps_done;
  for (std::size_t i = last; i-- > 0;)
    for (const auto& u : plan.steps[i].undo) report.undo.push_back(u);
  return report;
}

}  // namespace hitl::board
