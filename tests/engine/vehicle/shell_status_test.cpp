// What a PX4 shell command returned, read from its output (engine/vehicle/shell_status.h).
#include "engine/vehicle/shell_status.h"

#include <gtest/gtest.h>

namespace hitl::vehicle {
namespace {

TEST(ShellStatus, NothingSaysItFailed) {
  EXPECT_EQ(shell_status("").code, 0);
  EXPECT_EQ(shell_status("Running: yes\n=== IMU Section ===\n").code, 0);
  // A line that only looks like it: no number, or 0.
  EXPECT_EQ(shell_status("Command 'x' failed, returned .\n").code, 0);
  EXPECT_EQ(shell_status("Command 'x' failed, returned 0.\n").code, 0);
  EXPECT_EQ(shell_status("  Command 'x' failed, returned 1.\n").code, 0);
}

TEST(ShellStatus, PxhReturnCode) {
  const auto s = shell_status("Running: no\nCommand 'dsp_hitl' failed, returned 1.\n");
  EXPECT_EQ(s.code, 1);
  EXPECT_EQ(s.line, "Command 'dsp_hitl' failed, returned 1.");
  EXPECT_EQ(shell_status("Command 'qshell' failed, returned -1.\r\n").code, -1);
}

TEST(ShellStatus, UnknownCommand) {
  EXPECT_EQ(shell_status("Invalid command: foo\ntype 'help' for a list of commands\n").code, -1);
  const auto s = shell_status("nsh: foo: command not found\n");
  EXPECT_EQ(s.code, -1);
  EXPECT_EQ(s.line, "nsh: foo: command not found");
}

}  // namespace
}  // namespace hitl::vehicle
