#include <gtest/gtest.h>

#include <algorithm>

#include "engine/board/board_plan.h"
#include "engine/board/board_state.h"

namespace hitl::board {
namespace {

/// A new VOXL2: ModalAI's PX4 and vision-hub enabled and running, no HITL package.
BoardSurvey new_board() {
  BoardSurvey s;
  s.installed = {{"voxl-hitl-vio-server", ""}, {"voxl-hitl-px4-scripts", ""}};
  s.services = {{"voxl-px4", true, true}, {"voxl-hitl-vio-server", false, false}, {"voxl-vision-hub", true, true}, {"voxl-px4-hitl", false, false}};
  s.vision_hub_text = "{\"en_vio\": true, \"other\": 7}\n";
  return s;
}

std::vector<PackageFile> packages() {
  return {*package_file("/out/voxl-hitl-vio-server_0.1.0_arm64.deb"), *package_file("/out/voxl-hitl-px4-scripts_0.1.0_arm64.deb")};
}

std::vector<std::string> shell_commands(const BoardPlan& plan) {
  std::vector<std::string> out;
  for (const auto& s : plan.steps)
    for (const auto& a : s.actions)
      if (a.kind == ActionKind::Shell) out.push_back(a.command);
  return out;
}

std::size_t index_of(const std::vector<std::string>& v, const std::string& prefix) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i].rfind(prefix, 0) == 0) return i;
  ADD_FAILURE() << "no command starting with " << prefix;
  return v.size();
}

TEST(PackageFile, NameAndVersionFromCpacksFileName) {
  auto p = package_file("/x/voxl-hitl-px4-scripts_0.1.0_arm64.deb");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->name, "voxl-hitl-px4-scripts");
  EXPECT_EQ(p->version, "0.1.0");
  for (const char* bad : {"foo.deb", "voxl.tar.gz", "_1_arm64.deb", "a__arm64.deb"}) EXPECT_FALSE(package_file(bad)) << bad;
}

TEST(InstallPlan, RecordsAndBacksUpBeforeItChangesAnythingThenInstallsConfiguresEnables) {
  auto plan = make_install_plan(new_board(), {packages()});
  ASSERT_TRUE(plan) << plan.error().message;
  const auto cmds = shell_commands(*plan);
  const auto backup = index_of(cmds, "cp -p /etc/modalai/voxl-vision-hub.conf /data/hitl-board/voxl-vision-hub.conf.orig");
  const auto dpkg = index_of(cmds, "dpkg -i /tmp/hitl-board/voxl-hitl-vio-server_0.1.0_arm64.deb /tmp/hitl-board/voxl-hitl-px4-scripts_0.1.0_arm64.deb");
  const auto hub = index_of(cmds, "cp /tmp/hitl-board/voxl-vision-hub.conf /etc/modalai/voxl-vision-hub.conf");
  const auto vio = index_of(cmds, "cp /tmp/hitl-board/voxl-hitl-vio-server.conf /etc/modalai/voxl-hitl-vio-server.conf");
  const auto enable = index_of(cmds, "systemctl enable voxl-vision-hub");
  EXPECT_LT(backup, dpkg);
  EXPECT_LT(dpkg, vio);
  EXPECT_LT(vio, hub);
  EXPECT_LT(hub, enable);
  EXPECT_EQ(cmds.back(), "rm -rf /tmp/hitl-board");
  // The vio server's config did not exist: its undo removes it; vision-hub's puts the backup back.
  const auto lines = plan_lines(*plan);
  const auto has = [&](const std::string& text) { return std::find(lines.begin(), lines.end(), text) != lines.end(); };
  EXPECT_TRUE(has("      undo: $ cp -p /data/hitl-board/voxl-vision-hub.conf.orig /etc/modalai/voxl-vision-hub.conf"));
  EXPECT_TRUE(has("      undo: $ rm -f /etc/modalai/voxl-hitl-vio-server.conf"));
  EXPECT_TRUE(has("      undo: $ dpkg --purge voxl-hitl-vio-server voxl-hitl-px4-scripts"));
  EXPECT_TRUE(has("      undo: $ systemctl disable voxl-hitl-vio-server"));
  EXPECT_FALSE(has("      undo: $ systemctl disable voxl-vision-hub")) << "it was enabled before";
  EXPECT_TRUE(has("      en_hitl: absent -> true"));
  EXPECT_TRUE(has("      en_vio: true -> false"));
  EXPECT_EQ(plan->undo_command, "hitl board restore");
}

TEST(InstallPlan, ASecondInstallKeepsTheFirstRecordAndBackup) {
  auto board = new_board();
  board.state_text = "package voxl-hitl-vio-server -\nfile /etc/modalai/voxl-vision-hub.conf present\n";
  auto plan = make_install_plan(board, {packages()});
  ASSERT_TRUE(plan);
  for (const auto& c : shell_commands(*plan)) EXPECT_EQ(c.find("cp -p /etc/modalai"), std::string::npos) << c;
  ASSERT_FALSE(plan->notes.empty());
  EXPECT_NE(plan->notes[0].find("kept"), std::string::npos);
}

TEST(InstallPlan, AVisionHubConfigThatIsNotJsonStopsBeforeAnyStep) {
  auto board = new_board();
  board.vision_hub_text = "{ broken";
  auto plan = make_install_plan(board, {packages()});
  ASSERT_FALSE(plan);
  EXPECT_EQ(plan.error().kind, ErrorKind::Input);
}

TEST(StartPlan, TheSpecsOrderPx4ThenTheVioServerThenVisionHub) {
  const auto plan = make_start_plan(new_board(), {false, 30});
  const auto cmds = shell_commands(plan);
  const auto stop = index_of(cmds, "systemctl stop voxl-px4");
  const auto px4 = index_of(cmds, "systemctl reset-failed voxl-px4-hitl 2>/dev/null; systemd-run --unit=voxl-px4-hitl /usr/bin/voxl-px4-hitl start --daemon");
  const auto vio = index_of(cmds, "systemctl restart voxl-hitl-vio-server");
  const auto hub = index_of(cmds, "systemctl restart voxl-vision-hub");
  EXPECT_LT(stop, px4);
  EXPECT_LT(px4, vio);
  EXPECT_LT(vio, hub);
  // The wait and the parameters come between PX4 and the services.
  std::vector<ActionKind> kinds;
  for (const auto& s : plan.steps)
    for (const auto& a : s.actions) kinds.push_back(a.kind);
  const auto wait = std::find(kinds.begin(), kinds.end(), ActionKind::WaitForPx4) - kinds.begin();
  const auto params = std::find(kinds.begin(), kinds.end(), ActionKind::HitlParams) - kinds.begin();
  EXPECT_LT(wait, params);
  EXPECT_EQ(plan.undo_command, "hitl board stop");
  const auto reset = make_start_plan(new_board(), {true, 30});
  EXPECT_NE(shell_commands(reset)[1].find("start --daemon --reset-params"), std::string::npos);
}

TEST(StopPlan, ReverseOrderOnlyWhatRuns) {
  auto board = new_board();
  board.services = {{"voxl-px4", true, false}, {"voxl-hitl-vio-server", true, true}, {"voxl-vision-hub", true, true}, {"voxl-px4-hitl", false, true}};
  const auto cmds = shell_commands(make_stop_plan(board));
  EXPECT_EQ(cmds, (std::vector<std::string>{"systemctl stop voxl-vision-hub", "systemctl stop voxl-hitl-vio-server", "systemctl stop voxl-px4-hitl",
                                            "systemctl start voxl-px4"}));
  // voxl-px4 disabled (not how this board boots): left stopped.
  board.services[0].enabled = false;
  EXPECT_EQ(shell_commands(make_stop_plan(board)).size(), 3u);
}

TEST(RestorePlan, BackFromTheRecord) {
  auto board = new_board();
  board.state_text = format_board_state(state_from_survey(new_board()));
  // After install and start: packages in, vio server enabled and running, PX4 HITL running.
  board.installed = {{"voxl-hitl-vio-server", "0.1.0"}, {"voxl-hitl-px4-scripts", "0.1.0"}};
  board.services = {{"voxl-px4", true, false}, {"voxl-hitl-vio-server", true, true}, {"voxl-vision-hub", true, true}, {"voxl-px4-hitl", false, true}};
  auto plan = make_restore_plan(board, {});
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_EQ(shell_commands(*plan),
            (std::vector<std::string>{"systemctl stop voxl-vision-hub", "systemctl stop voxl-hitl-vio-server", "systemctl stop voxl-px4-hitl",
                                      "systemctl disable voxl-hitl-vio-server", "dpkg --purge voxl-hitl-vio-server voxl-hitl-px4-scripts",
                                      "cp -p /data/hitl-board/voxl-vision-hub.conf.orig /etc/modalai/voxl-vision-hub.conf", "systemctl start voxl-px4",
                                      "systemctl start voxl-vision-hub", "rm -rf /data/hitl-board"}));
  auto keep = make_restore_plan(board, {true, true});
  ASSERT_TRUE(keep);
  const auto kept = shell_commands(*keep);
  EXPECT_EQ(std::count(kept.begin(), kept.end(), "systemctl disable voxl-hitl-vio-server"), 1);
  EXPECT_EQ(std::count(kept.begin(), kept.end(), "rm -f /etc/modalai/voxl-hitl-vio-server.conf"), 1);
  EXPECT_EQ(std::count(kept.begin(), kept.end(), "rm -f /data/px4/param/hitl_parameters"), 1);
  EXPECT_EQ(std::count_if(kept.begin(), kept.end(), [](const std::string& c) { return c.rfind("dpkg", 0) == 0; }), 0);
}

TEST(RestorePlan, NoRecordNothingToRestore) {
  auto plan = make_restore_plan(new_board(), {});
  ASSERT_FALSE(plan);
  EXPECT_NE(plan.error().message.find("nothing to restore"), std::string::npos);
}

}  // namespace
}  // namespace hitl::board
