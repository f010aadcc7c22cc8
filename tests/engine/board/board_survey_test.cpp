#include <gtest/gtest.h>

#include "engine/board/board_state.h"
#include "engine/board/board_survey.h"
#include "engine/board/restart_params.h"
#include "tests/engine/board/scripted_shell.h"

namespace hitl::board {
namespace {

TEST(BoardSurvey, ReadsPackagesServicesAndFiles) {
  test::ScriptedShell shell;
  shell.answers["dpkg-query"] = {1, "voxl-hitl-vio-server\t0.1.0\nvoxl-hitl-px4-scripts\t\n", ""};
  shell.answers["for s in"] = {0, "voxl-px4 enabled active\nvoxl-hitl-vio-server disabled inactive\nvoxl-vision-hub enabled active\nvoxl-px4-hitl  inactive\n", ""};
  shell.answers["test -e /etc/modalai/voxl-vision-hub.conf"] = {0, "{\"a\": 1}\n", ""};
  shell.answers["test -e /etc/modalai/voxl-hitl-vio-server.conf"] = {3, "", ""};
  shell.answers["test -e /data/hitl-board/state"] = {3, "", ""};
  auto survey = survey_board(shell);
  ASSERT_TRUE(survey) << survey.error().message;
  EXPECT_EQ(survey->version("voxl-hitl-vio-server"), "0.1.0");
  EXPECT_EQ(survey->version("voxl-hitl-px4-scripts"), "");
  EXPECT_TRUE(survey->service("voxl-px4").enabled);
  EXPECT_TRUE(survey->service("voxl-vision-hub").active);
  EXPECT_FALSE(survey->service("voxl-hitl-vio-server").enabled);
  EXPECT_FALSE(survey->service("voxl-px4-hitl").active);
  EXPECT_EQ(*survey->vision_hub_text, "{\"a\": 1}\n");
  EXPECT_FALSE(survey->vio_server_text);
  EXPECT_FALSE(survey->state_text);
  EXPECT_EQ(shell.log.size(), survey_commands().size());
  for (const auto& line : shell.log) EXPECT_EQ(line.find("rm "), std::string::npos) << "the survey only reads: " << line;
}

TEST(BoardSurvey, AHugeConfigurationFileIsRefusedNotRead) {
  test::ScriptedShell shell;
  shell.answers["test -e /etc/modalai/voxl-vision-hub.conf"] = {0, std::string((1 << 20) + 1, ' '), ""};
  auto survey = survey_board(shell);
  ASSERT_FALSE(survey);
  EXPECT_EQ(survey.error().kind, ErrorKind::Input);
  EXPECT_NE(survey.error().message.find("over 1024 KiB"), std::string::npos) << survey.error().message;
  bool bounded = false;
  for (const auto& line : shell.log) bounded = bounded || line.find("head -c 1048577 /etc/modalai/voxl-vision-hub.conf") != std::string::npos;
  EXPECT_TRUE(bounded);
}

TEST(BoardState, RoundTripsAndRejectsWhatInstallNeverWrites) {
  BoardSurvey survey;
  survey.installed = {{"voxl-hitl-vio-server", ""}, {"voxl-hitl-px4-scripts", "0.0.9"}};
  survey.services = {{"voxl-px4", true, true}, {"voxl-vision-hub", true, false}};
  survey.vision_hub_text = "{}";
  const auto state = state_from_survey(survey);
  const std::string text = format_board_state(state);
  EXPECT_NE(text.find("package voxl-hitl-vio-server -\n"), std::string::npos) << text;
  EXPECT_NE(text.find("service voxl-vision-hub enabled inactive\n"), std::string::npos) << text;
  EXPECT_NE(text.find("file /etc/modalai/voxl-vision-hub.conf present\n"), std::string::npos) << text;
  auto back = parse_board_state(text);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(format_board_state(*back), text);
  auto bad = parse_board_state("package a b c\n");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("line 1"), std::string::npos);
}

TEST(RestartParams, PX4sRebootRequiredParameters) {
  for (const char* name : {"SYS_HITL", "SYS_AUTOSTART", "IMU_GYRO_RATEMAX", "EKF2_MAG_TYPE", "CBRK_SUPPLY_CHK", "CBRK_IO_SAFETY", "SENS_EN_GPSSIM"})
    EXPECT_TRUE(needs_restart(name)) << name;
  for (const char* name : {"CAL_ACC0_ID", "EKF2_GPS_CTRL", "CA_ROTOR_COUNT", "COM_ARM_MAG_STR", "SYS_HITLX"}) EXPECT_FALSE(needs_restart(name)) << name;
  EXPECT_EQ(restart_params({"CAL_ACC0_ID", "SYS_HITL", "CBRK_IO_SAFETY"}), (std::vector<std::string>{"SYS_HITL", "CBRK_IO_SAFETY"}));
}

}  // namespace
}  // namespace hitl::board
