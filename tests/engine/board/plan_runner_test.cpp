#include <gtest/gtest.h>

#include "engine/board/plan_runner.h"
#include "tests/engine/board/scripted_shell.h"

namespace hitl::board {
namespace {

BoardSurvey new_board() {
  BoardSurvey s;
  s.services = {{"voxl-px4", true, true}, {"voxl-vision-hub", true, true}};
  s.vision_hub_text = "{\"keep\": 1}";
  return s;
}

InstallOptions packages() {
  return {{*package_file("/out/voxl-hitl-vio-server_0.1.0_arm64.deb"), *package_file("/out/voxl-hitl-px4-scripts_0.1.0_arm64.deb")}};
}

TEST(PlanRunner, RunsEveryStepInOrderAndPushesTheGeneratedFiles) {
  auto plan = make_install_plan(new_board(), packages());
  ASSERT_TRUE(plan);
  test::ScriptedShell shell;
  std::vector<std::size_t> said;
  const auto report = run_plan(*plan, shell, {}, {[&](std::size_t i) { said.push_back(i); }, {}});
  EXPECT_TRUE(report.ok) << report.error;
  EXPECT_EQ(report.steps_done, plan->steps.size());
  EXPECT_EQ(said.size(), plan->steps.size());
  EXPECT_NE(shell.pushed["/tmp/hitl-board/voxl-vision-hub.conf"].find("\"keep\": 1"), std::string::npos);
  EXPECT_NE(shell.pushed["/data/hitl-board/state"].find("service voxl-px4 enabled active"), std::string::npos);
}

TEST(PlanRunner, AFailureStopsAndSaysWhatChangedAndHowToUndoIt) {
  auto plan = make_install_plan(new_board(), packages());
  ASSERT_TRUE(plan);
  test::ScriptedShell shell;
  shell.fail_prefix = "dpkg -i";
  const auto report = run_plan(*plan, shell, {}, {});
  EXPECT_FALSE(report.ok);
  ASSERT_TRUE(report.failed_step);
  EXPECT_EQ(plan->steps[*report.failed_step].name, "install the packages");
  EXPECT_EQ(report.error, "exit 1");
  EXPECT_NE(report.board_output.find("dpkg: error"), std::string::npos);
  for (const auto& line : shell.log) EXPECT_EQ(line.find("systemctl enable"), std::string::npos) << "ran past the failure: " << line;
  // Undo: the failed step's first, then the record's.
  ASSERT_GE(report.undo.size(), 2u);
  EXPECT_EQ(report.undo[0], "dpkg --purge voxl-hitl-vio-server voxl-hitl-px4-scripts");
  EXPECT_EQ(report.undo[1], "rm -rf /data/hitl-board");
  EXPECT_EQ(report.changed.back(), "install the packages");
}

TEST(PlanRunner, AParameterThatNeedsARestartRestartsPx4AndWaitsAgain) {
  BoardSurvey board = new_board();
  auto plan = make_start_plan(board, {false, 5});
  test::ScriptedShell shell;
  int waits = 0;
  HostActions host{[&]() -> Status {
                     ++waits;
                     return Ok{};
                   },
                   []() -> Expected<std::vector<std::string>> { return std::vector<std::string>{"CAL_ACC0_ID", "SYS_HITL"}; }};
  std::vector<std::string> lines;
  const auto report = run_plan(plan, shell, host, {{}, [&](const std::string& l) { lines.push_back(l); }});
  EXPECT_TRUE(report.ok) << report.error;
  EXPECT_EQ(waits, 2);
  EXPECT_EQ(report.params_restart, (std::vector<std::string>{"SYS_HITL"}));
  EXPECT_NE(std::find(shell.log.begin(), shell.log.end(), "$ systemctl restart voxl-px4-hitl"), shell.log.end());
  bool said = false;
  for (const auto& l : lines) said = said || l.find("SYS_HITL takes effect only when PX4 starts again: restarting PX4") != std::string::npos;
  EXPECT_TRUE(said);

  // Nothing to set: no restart.
  test::ScriptedShell quiet;
  waits = 0;
  host.hitl_params = []() -> Expected<std::vector<std::string>> { return std::vector<std::string>{}; };
  EXPECT_TRUE(run_plan(plan, quiet, host, {}).ok);
  EXPECT_EQ(waits, 1);
  EXPECT_EQ(std::find(quiet.log.begin(), quiet.log.end(), "$ systemctl restart voxl-px4-hitl"), quiet.log.end());
}

TEST(PlanRunner, PX4NotComingUpShowsTheBoardsOwnOutput) {
  auto plan = make_start_plan(new_board(), {false, 5});
  test::ScriptedShell shell;
  shell.answers["journalctl"] = {0, "voxl-px4-hitl: error: step 5: 'qshell dsp_hitl start' failed (exit 1)\n", ""};
  HostActions host{[]() -> Status { return Error{"PX4 not ready after 5 s: no HEARTBEAT"}; }, {}};
  const auto report = run_plan(plan, shell, host, {});
  EXPECT_FALSE(report.ok);
  EXPECT_NE(report.error.find("no HEARTBEAT"), std::string::npos);
  EXPECT_NE(report.board_output.find("step 5"), std::string::npos) << report.board_output;
  EXPECT_EQ(report.undo.front(), "systemctl stop voxl-px4-hitl");
  EXPECT_EQ(report.undo.back(), "systemctl start voxl-px4");
}

}  // namespace
}  // namespace hitl::board
