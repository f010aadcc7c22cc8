#include "engine/board/board_plan.h"

#include <cstdio>
#include <fstream>

#include "engine/board/board_facts.h"
#include "engine/board/board_state.h"
#include "engine/board/restart_params.h"
#include "engine/board/vision_hub_config.h"

namespace hitl::board {
namespace {

std::string basename_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string staged(const std::string& name) { return std::string(kStagingDir) + "/" + name; }

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

/// The step that puts a generated file in place: pushed to the staging directory, then copied.
BoardStep write_file_step(std::string name, const std::string& target, std::string content, const std::string& what,
                          bool present_before) {
  BoardStep step;
  step.name = std::move(name);
  const std::string stage = staged(basename_of(target));
  step.actions.push_back(BoardAction::push_text(std::move(content), what, stage));
  step.actions.push_back(BoardAction::shell("cp " + stage + " " + target));
  step.undo.push_back(present_before ? "cp -p " + backup_path(target) + " " + target : "rm -f " + target);
  return step;
}

}  // namespace

BoardAction BoardAction::shell(std::string command) {
  BoardAction a;
  a.kind = ActionKind::Shell;
  a.command = std::move(command);
  return a;
}

BoardAction BoardAction::push_file(std::string local_path, std::string remote_path) {
  BoardAction a;
  a.kind = ActionKind::Push;
  a.local_path = std::move(local_path);
  a.remote_path = std::move(remote_path);
  return a;
}

BoardAction BoardAction::push_text(std::string content, std::string name, std::string remote_path) {
  BoardAction a;
  a.kind = ActionKind::Push;
  a.content = std::move(content);
  a.content_name = std::move(name);
  a.remote_path = std::move(remote_path);
  return a;
}

std::string BoardAction::text() const {
  std::string t;
  switch (kind) {
    case ActionKind::Shell: t = "$ " + command; break;
    case ActionKind::Push:
      t = "push " + (local_path.empty() ? "(" + content_name + ", " + std::to_string(content.size()) + " bytes)" : local_path) + " -> " +
          remote_path;
      break;
    case ActionKind::WaitForPx4: t = "wait for PX4: HEARTBEAT on its GCS instance, then `" + command + "` says Running: yes"; break;
    case ActionKind::HitlParams: t = "check the HITL parameters (hitl params check) and set what differs (hitl params reset)"; break;
  }
  return only_after_restart_params ? t + "   [only when a parameter that needs a restart was set]" : t;
}

std::vector<std::string> step_lines(const BoardPlan& plan, std::size_t index) {
  const BoardStep& step = plan.steps[index];
  std::vector<std::string> lines{"[" + std::to_string(index + 1) + "/" + std::to_string(plan.steps.size()) + "] " + step.name};
  for (const auto& d : step.details) lines.push_back("      " + d);
  for (const auto& a : step.actions) lines.push_back("      " + a.text());
  return lines;
}

std::vector<std::string> plan_lines(const BoardPlan& plan) {
  std::vector<std::string> lines;
  for (const auto& n : plan.notes) lines.push_back("note: " + n);
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    auto s = step_lines(plan, i);
    lines.insert(lines.end(), s.begin(), s.end());
    for (const auto& u : plan.steps[i].undo) lines.push_back("      undo: $ " + u);
  }
  return lines;
}

Expected<PackageFile> package_file(const std::string& path) {
  const std::string name = basename_of(path);
  const auto first = name.find('_');
  const auto second = first == std::string::npos ? std::string::npos : name.find('_', first + 1);
  if (name.size() < 5 || name.substr(name.size() - 4) != ".deb" || first == 0 || second == std::string::npos || second == first + 1)
    return Error::input(path + ": not a Debian package file name (NAME_VERSION_ARCH.deb, as cpack names them)");
  return PackageFile{path, name.substr(0, first), name.substr(first + 1, second - first - 1)};
}

Expected<PackageFile> local_package(const std::string& path) {
  auto p = package_file(path);
  if (!p) return p.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::input(path + ": cannot be read");
  return p;
}

Expected<std::vector<PackageFile>> build_packages(const std::string& dir, const std::string& version) {
  std::vector<PackageFile> files;
  for (const char* name : kHitlPackages) {
    const std::string path = (dir.empty() ? std::string(".") : dir) + "/" + name + "_" + version + "_arm64.deb";
    if (!std::ifstream(path, std::ios::binary))
      return Error::input("no " + path + ": build this version's board packages (`cmake -S target -B DIR ...; cpack -G DEB` in DIR, "
                          "docs/board-packages.md) and give --packages DIR, or name the .deb files");
    files.push_back(PackageFile{path, name, version});
  }
  return files;
}

Expected<BoardPlan> make_install_plan(const BoardSurvey& survey, const InstallOptions& options) {
  auto hub = edit_vision_hub_config(survey.vision_hub_text.value_or(""));
  if (!hub) return hub.error();
  const BoardState before = state_from_survey(survey);
  BoardPlan plan;
  plan.command = "install";
  plan.undo_command = "hitl board restore";

  BoardStep push;
  push.name = "push the packages to the board (" + std::string(kStagingDir) + ")";
  push.changes_board = false;
  push.actions.push_back(BoardAction::shell(std::string("mkdir -p ") + kStagingDir));
  for (const auto& p : options.packages) push.actions.push_back(BoardAction::push_file(p.path, staged(basename_of(p.path))));
  push.undo.push_back(std::string("rm -rf ") + kStagingDir);
  plan.steps.push_back(push);

  if (survey.state_text) {
    plan.notes.push_back(std::string("the board already has the record of an earlier install (") + kStateFile +
                         "): it is kept, so hitl board restore goes back to the board before that install");
  } else {
    BoardStep record;
    record.name = std::string("record the board as it is and back up its configuration (") + kBackupDir + ")";
    record.actions.push_back(BoardAction::shell(std::string("mkdir -p ") + kBackupDir));
    for (const auto& [path, present] : before.files_present)
      if (present) record.actions.push_back(BoardAction::shell("cp -p " + path + " " + backup_path(path)));
    record.actions.push_back(BoardAction::push_text(format_board_state(before), "the record", kStateFile));
    record.undo.push_back(std::string("rm -rf ") + kBackupDir);
    plan.steps.push_back(record);
  }

  BoardStep install;
  install.name = "install the packages";
  std::string dpkg = "dpkg -i";
  std::string purge;
  for (const auto& p : options.packages) {
    dpkg += " " + staged(basename_of(p.path));
    const std::string was = survey.version(p.name);
    install.details.push_back(p.name + " " + (was.empty() ? "(not installed)" : was) + " -> " + p.version);
    if (was.empty()) purge += " " + p.name;
  }
  install.actions.push_back(BoardAction::shell(dpkg));
  if (!purge.empty()) install.undo.push_back("dpkg --purge" + purge);
  plan.steps.push_back(install);

  // A second install finds the files already edited: their originals are the first install's backups.
  BoardState recorded = before;
  if (survey.state_text) {
    auto earlier = parse_board_state(*survey.state_text);
    if (!earlier) return earlier.error();
    recorded = *earlier;
  }
  const auto had = [&](const char* path) { return recorded.files_present[path]; };
  plan.steps.push_back(write_file_step("write " + std::string(kVioServerConf) + " (receiver 0.0.0.0:14570)", kVioServerConf,
                                       vio_server_config_text(), "voxl-hitl-vio-server.conf", had(kVioServerConf)));
  BoardStep hub_step = write_file_step("set voxl-vision-hub's HITL keys in " + std::string(kVisionHubConf) + ", keeping the others",
                                       kVisionHubConf, hub->text, "voxl-vision-hub.conf, edited", had(kVisionHubConf));
  for (const auto& k : hub->keys) hub_step.details.push_back(k.key + ": " + k.from + " -> " + k.to + (k.changes() ? "" : " (unchanged)"));
  plan.steps.push_back(hub_step);

  BoardStep enable;
  enable.name = "enable the services";
  enable.actions.push_back(BoardAction::shell("systemctl daemon-reload"));
  for (const char* s : {kVioServerService, kVisionHubService}) {
    enable.actions.push_back(BoardAction::shell(std::string("systemctl enable ") + s));
    if (!survey.service(s).enabled) enable.undo.push_back(std::string("systemctl disable ") + s);
  }
  plan.steps.push_back(enable);

  BoardStep clean;
  clean.name = "remove " + std::string(kStagingDir);
  clean.changes_board = false;
  clean.actions.push_back(BoardAction::shell(std::string("rm -rf ") + kStagingDir));
  plan.steps.push_back(clean);
  return plan;
}

BoardPlan make_start_plan(const BoardSurvey& survey, const StartOptions& options) {
  BoardPlan plan;
  plan.command = "start";
  plan.undo_command = "hitl board stop";
  if (survey.service(kPx4Service).active) {
    BoardStep stop;
    stop.name = std::string("stop the normal PX4 (") + kPx4Service + "): one PX4 at a time";
    stop.actions.push_back(BoardAction::shell(std::string("systemctl stop ") + kPx4Service));
    stop.undo.push_back(std::string("systemctl start ") + kPx4Service);
    plan.steps.push_back(stop);
  }
  if (survey.version("voxl-hitl-px4-scripts").empty())
    plan.notes.push_back(std::string("voxl-hitl-px4-scripts is not installed: ") + kPx4HitlScript +
                         " is whatever the board has (voxl-px4's own, if any); hitl board install puts hitl's in place");
  const bool running = survey.service(kPx4HitlUnit).active;
  BoardStep px4;
  if (running && !options.reset_params) {
    px4.name = std::string("PX4 in HITL is already running (") + kPx4HitlUnit + ")";
    px4.changes_board = false;
  } else {
    px4.name = std::string("start PX4 in HITL: voxl-px4-hitl start, as the unit ") + kPx4HitlUnit +
               (options.reset_params ? " (--reset-params: the HITL defaults loaded again)" : "");
    if (running) px4.actions.push_back(BoardAction::shell(std::string("systemctl stop ") + kPx4HitlUnit));
    px4.actions.push_back(BoardAction::shell(std::string("systemctl reset-failed ") + kPx4HitlUnit + " 2>/dev/null; systemd-run --unit=" +
                                             kPx4HitlUnit + " " + kPx4HitlScript + " start --daemon" +
                                             (options.reset_params ? " --reset-params" : "")));
    px4.undo.push_back(std::string("systemctl stop ") + kPx4HitlUnit);
  }
  plan.steps.push_back(px4);

  BoardAction wait;
  wait.kind = ActionKind::WaitForPx4;
  wait.command = "qshell dsp_hitl status";
  wait.diagnose = std::string("journalctl -u ") + kPx4HitlUnit + " -n 40 --no-pager";
  BoardStep waiting;
  waiting.name = "wait for PX4 and dsp_hitl (up to " + seconds_text(options.timeout_s) + " s)";
  waiting.changes_board = false;
  waiting.actions.push_back(wait);
  plan.steps.push_back(waiting);

  BoardStep params;
  params.name = "the HITL parameters: set what differs; restart PX4 when one takes effect only on restart";
  params.details.push_back("need a restart: " + restart_param_rule_text());
  BoardAction check;
  check.kind = ActionKind::HitlParams;
  params.actions.push_back(check);
  BoardAction restart = BoardAction::shell(std::string("systemctl restart ") + kPx4HitlUnit);
  restart.only_after_restart_params = true;
  params.actions.push_back(restart);
  BoardAction rewait = wait;
  rewait.only_after_restart_params = true;
  params.actions.push_back(rewait);
  params.changes_board = true;
  plan.steps.push_back(params);

  for (const char* s : {kVioServerService, kVisionHubService}) {
    BoardStep start;
    start.name = std::string("start ") + s + (s == kVisionHubService ? " (after the VIO server, whose pipe it opens at start)" : "");
    start.actions.push_back(BoardAction::shell(std::string("systemctl restart ") + s));
    start.undo.push_back(std::string("systemctl stop ") + s);
    plan.steps.push_back(start);
  }
  return plan;
}

BoardPlan make_stop_plan(const BoardSurvey& survey) {
  BoardPlan plan;
  plan.command = "stop";
  plan.undo_command = "hitl board start";
  for (const char* s : {kVisionHubService, kVioServerService, kPx4HitlUnit}) {
    BoardStep step;
    if (!survey.service(s).active) {
      step.name = std::string(s) + " is not running";
      step.changes_board = false;
    } else {
      step.name = std::string("stop ") + s;
      step.actions.push_back(BoardAction::shell(std::string("systemctl stop ") + s));
      step.undo.push_back(s == std::string(kPx4HitlUnit) ? std::string("hitl board start") : std::string("systemctl start ") + s);
    }
    plan.steps.push_back(step);
  }
  // The board as it boots: the normal PX4 again, when it is enabled (start stopped it).
  const ServiceState px4 = survey.service(kPx4Service);
  if (px4.enabled && !px4.active) {
    BoardStep normal;
    normal.name = std::string("start the normal PX4 (") + kPx4Service + "), as the board boots";
    normal.actions.push_back(BoardAction::shell(std::string("systemctl start ") + kPx4Service));
    normal.undo.push_back(std::string("systemctl stop ") + kPx4Service);
    plan.steps.push_back(normal);
  }
  return plan;
}

Expected<BoardPlan> make_restore_plan(const BoardSurvey& survey, const RestoreOptions& options) {
  if (!survey.state_text)
    return Error::failed(std::string("nothing to restore: the board has no record of a hitl board install (") + kStateFile + ")");
  auto before = parse_board_state(*survey.state_text);
  if (!before) return before.error();
  BoardPlan plan;
  plan.command = "restore";
  plan.after_failure = std::string("the record stays until the last step: run hitl board restore again once the failure is fixed");

  BoardStep stop;
  stop.name = "stop the HITL services";
  stop.changes_board = false;
  for (const char* s : {kVisionHubService, kVioServerService, kPx4HitlUnit})
    if (survey.service(s).active) stop.actions.push_back(BoardAction::shell(std::string("systemctl stop ") + s));
  if (stop.actions.empty()) stop.name = "the HITL services are not running";
  stop.changes_board = !stop.actions.empty();
  plan.steps.push_back(stop);

  const bool removing = !options.keep_packages;
  bool vio_removed = false;
  if (removing) {
    const auto it = before->packages.find(kVioServerService);
    vio_removed = it == before->packages.end() || it->second.empty();
  }
  // Before the purge, while every unit is still there (a removed unit's enable link would stay).
  BoardStep enabled;
  enabled.name = "enable and disable the services as they were";
  for (const auto& was : before->services)
    if (survey.service(was.name).enabled != was.enabled)
      enabled.actions.push_back(BoardAction::shell(std::string("systemctl ") + (was.enabled ? "enable " : "disable ") + was.name));
  if (enabled.actions.empty()) {
    enabled.name = "the services are enabled as they were";
    enabled.changes_board = false;
  }
  plan.steps.push_back(enabled);
  if (removing) {
    BoardStep purge;
    purge.name = "remove the HITL packages";
    std::string names;
    for (const char* p : kHitlPackages) {
      const auto it = before->packages.find(p);
      const std::string was = it == before->packages.end() ? "" : it->second;
      if (!was.empty()) {
        plan.notes.push_back(std::string(p) + " was installed before hitl board install (" + was + "): left installed");
      } else if (!survey.version(p).empty()) {
        names += std::string(" ") + p;
      }
    }
    if (names.empty()) {
      purge.name = "no HITL package to remove";
      purge.changes_board = false;
    } else {
      purge.actions.push_back(BoardAction::shell("dpkg --purge" + names));
    }
    plan.steps.push_back(purge);
  } else {
    plan.notes.push_back("--keep: the HITL packages stay installed");
  }

  // After the purge: dpkg --purge removes a conffile, which may be an original to put back.
  BoardStep files;
  files.name = "put the configuration back from " + std::string(kBackupDir);
  for (const auto& [path, present] : before->files_present) {
    if (present) {
      files.actions.push_back(BoardAction::shell("cp -p " + backup_path(path) + " " + path));
    } else if (path == kVisionHubConf || !removing) {
      files.actions.push_back(BoardAction::shell("rm -f " + path));
    }  // the vio server's conffile goes with its package (dpkg --purge)
  }
  plan.steps.push_back(files);

  BoardStep running;
  running.name = "start the services that were running";
  for (const auto& was : before->services) {
    if (was.name == kVioServerService && vio_removed) continue;  // its unit left with the package
    const bool active_now = survey.service(was.name).active && was.name == kPx4Service;  // step 1 stopped the others
    if (was.active && !active_now) running.actions.push_back(BoardAction::shell("systemctl start " + was.name));
  }
  if (running.actions.empty()) {
    running.name = "no service to start: none of them was running";
    running.changes_board = false;
  }
  plan.steps.push_back(running);

  if (options.remove_params) {
    BoardStep params;
    params.name = "remove PX4's HITL parameters (the next hitl board start loads the HITL defaults)";
    params.actions.push_back(BoardAction::shell(std::string("rm -f ") + kHitlParamFile));
    plan.steps.push_back(params);
  } else {
    plan.notes.push_back(std::string("PX4's HITL parameters (") + kHitlParamFile +
                         ") are kept: voxl-px4's own parameters are another file, never touched; --params remove deletes them");
  }

  BoardStep forget;
  forget.name = "remove the record and the backup (" + std::string(kBackupDir) + ")";
  forget.actions.push_back(BoardAction::shell(std::string("rm -rf ") + kBackupDir));
  plan.steps.push_back(forget);
  return plan;
}

}  // namespace hitl::board
