// A `hitl board` subcommand as a plan: named steps, each with the exact board commands it runs (or
// the host's waits and parameter pushes), what it tells the user, and the commands that undo it.
// The plan is made from a survey (board_survey.h, read-only); `--dry-run` prints it, a real run
// executes exactly it (plan_runner.h). Nothing here talks to the board.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/board/board_survey.h"

namespace hitl::board {

enum class ActionKind {
  Shell,       ///< `command` on the board (adb shell)
  Push,        ///< a host file, or `content` generated here, to `remote_path` on the board
  WaitForPx4,  ///< the host waits for PX4's HEARTBEAT and `dsp_hitl status` "Running: yes"
  HitlParams,  ///< the host checks the HITL parameters and sets what differs (params_push.h)
};

struct BoardAction {
  ActionKind kind = ActionKind::Shell;
  std::string command;       ///< Shell
  std::string local_path;    ///< Push: a host file; empty when `content` is pushed
  std::string content;       ///< Push: generated text (written to a host temporary file first)
  std::string content_name;  ///< Push: what the generated text is ("voxl-vision-hub.conf, edited")
  std::string remote_path;   ///< Push
  /// Runs only when the HitlParams action before it set a parameter that takes effect on restart.
  bool only_after_restart_params = false;
  /// Run when this action fails, to show the board's own account ("journalctl -u voxl-px4-hitl ...").
  std::string diagnose;

  static BoardAction shell(std::string command);
  static BoardAction push_file(std::string local_path, std::string remote_path);
  static BoardAction push_text(std::string content, std::string name, std::string remote_path);
  /// One line: "$ systemctl start voxl-vision-hub", "push FILE -> REMOTE", "wait for PX4 ..."
  std::string text() const;
};

struct BoardStep {
  std::string name;                  ///< what it is said as, before it runs
  std::vector<std::string> details;  ///< lines shown under it (key changes, notes)
  std::vector<BoardAction> actions;
  std::vector<std::string> undo;     ///< board commands that undo it, in the order to run them
  bool changes_board = true;         ///< false: staging or waiting only
};

struct BoardPlan {
  std::string command;               ///< "install", "start", "stop", "restore"
  std::vector<std::string> notes;    ///< said before the steps (already installed, kept record, ...)
  std::vector<BoardStep> steps;
  /// The one command that undoes a partial run, when there is one ("hitl board restore").
  std::string undo_command;
  /// What to do after a failure when there is no undo command (restore: run it again).
  std::string after_failure;
};

/// The plan's text as --dry-run prints it and a real run says it, one line each:
/// notes, then "[i/n] NAME", its details and actions indented, "undo: ..." under steps that change the board.
std::vector<std::string> plan_lines(const BoardPlan& plan);
/// "[i/n] NAME" and the step's details and actions, as said before the step runs.
std::vector<std::string> step_lines(const BoardPlan& plan, std::size_t index);

/// A board package file: "voxl-hitl-vio-server_0.1.0_arm64.deb" -> name and version.
struct PackageFile {
  std::string path;
  std::string name;
  std::string version;
};
/// An Error of kind Input naming the file when its name is not NAME_VERSION_ARCH.deb.
Expected<PackageFile> package_file(const std::string& path);

/// This build's board packages in `dir`: NAME_VERSION_arm64.deb for each of kHitlPackages, as cpack
/// names them. An Error of kind Input naming the missing file and how to build it.
Expected<std::vector<PackageFile>> build_packages(const std::string& dir, const std::string& version);
/// A package file given by the user: its name must parse and the file must be readable.
Expected<PackageFile> local_package(const std::string& path);

struct InstallOptions {
  std::vector<PackageFile> packages;  ///< what to push and dpkg -i, in this order
};
/// install: push, record the board (first install only), dpkg -i, write the vio-server config, edit
/// vision-hub's, enable the services, clean up. An Error when vision-hub's file cannot be edited.
Expected<BoardPlan> make_install_plan(const BoardSurvey& survey, const InstallOptions& options);

struct StartOptions {
  bool reset_params = false;   ///< voxl-px4-hitl start --reset-params: load the HITL defaults again
  double timeout_s = 60.0;     ///< the wait for PX4 (said in the step)
};
/// start: stop voxl-px4, PX4 in HITL under systemd-run, wait, the HITL parameters (restart when
/// needed), the VIO server, vision-hub: the spec's step 9 order.
BoardPlan make_start_plan(const BoardSurvey& survey, const StartOptions& options);
/// stop: vision-hub, the VIO server, PX4 in HITL (the reverse order), then the normal PX4 when it is
/// enabled (the board as it boots).
BoardPlan make_stop_plan(const BoardSurvey& survey);

struct RestoreOptions {
  bool keep_packages = false;   ///< --keep
  bool remove_params = false;   ///< --params remove: delete PX4's HITL parameter file
};
/// restore: from the record install left; an Error (Failed) when there is none or it is unreadable.
Expected<BoardPlan> make_restore_plan(const BoardSurvey& survey, const RestoreOptions& options);

}  // namespace hitl::board
