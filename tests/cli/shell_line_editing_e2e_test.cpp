// `hitl shell` at a terminal (issue 18 point 11): line editing and history from libedit. In tmux
// against `hitl target`: Up recalls the last command, Ctrl-R finds an older one, the history
// outlives the session (in $XDG_STATE_HOME/hitl/shell_history), Ctrl-D exits 0.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/process.h"
#include "tests/support/tmux.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

bool has(const std::string& screen, const std::string& text) { return screen.find(text) != std::string::npos; }

std::size_t count_of(const std::string& screen, const std::string& text) {
  std::size_t n = 0;
  for (auto at = screen.find(text); at != std::string::npos; at = screen.find(text, at + 1)) ++n;
  return n;
}

TEST(ShellLineEditingE2E, UpRecallsCtrlRSearchesAndHistoryOutlivesTheSession) {
  const std::string tmux_bin = test::tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  const std::string gcs = std::to_string(test::free_udp_port());
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(test::free_udp_port()),
                       "--gcs-port", gcs, "--vio-port", "0"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  const auto state = std::filesystem::temp_directory_path() / ("hitl-shell-history-" + std::to_string(::getpid()));
  std::filesystem::remove_all(state);
  const std::string shell = "XDG_STATE_HOME=" + test::shell_quoted(state.string()) + " " + test::shell_quoted(test::hitl_binary()) +
                            " shell -i 127.0.0.1 --port " + gcs + " --local-port " +
                            std::to_string(test::free_udp_port()) +  // one port: the board answers the first it heard
                            "; echo HITL_EXIT=$?; sleep 60";
  std::string s;
  {
    test::Tmux tmux(tmux_bin, "shell-e2e-1");
    tmux.start(shell);
    ASSERT_TRUE(tmux.until([](const std::string& x) { return test::last_line(x) == "pxh>"; }, 20s, &s)) << s;
    tmux.keys({"param show SYS_HITL", "Enter"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return has(x, "SYS_HITL [") && test::last_line(x) == "pxh>"; }, 10s, &s)) << s;
    tmux.keys({"ver all", "Enter"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return has(x, "HW arch") && test::last_line(x) == "pxh>"; }, 10s, &s)) << s;
    // Up: the last command back on the line, not yet run.
    tmux.keys({"Up"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return test::last_line(x) == "pxh> ver all"; }, 5s, &s)) << s;
    tmux.keys({"Enter"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return count_of(x, "HW arch") == 2; }, 10s, &s)) << s;
    // Ctrl-R: an older command by what it contains.
    tmux.keys({"C-r"});
    tmux.keys({"-l", "SYS_"});
    tmux.keys({"Enter"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return count_of(x, "SYS_HITL [") == 2; }, 10s, &s)) << s;
    tmux.keys({"C-d"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return has(x, "HITL_EXIT="); }, 10s, &s)) << s;
    EXPECT_TRUE(has(s, "\nHITL_EXIT=0")) << s;  // on a line of its own
  }
  std::ifstream file(state / "hitl" / "shell_history");
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_NE(text.str().find("ver"), std::string::npos) << text.str();
  {
    // A new session: Up recalls what the last one ran.
    test::Tmux tmux(tmux_bin, "shell-e2e-2");
    tmux.start(shell);
    ASSERT_TRUE(tmux.until([](const std::string& x) { return test::last_line(x) == "pxh>"; }, 20s, &s)) << s;
    tmux.keys({"Up"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return test::last_line(x) == "pxh> param show SYS_HITL"; }, 5s, &s)) << s;
    tmux.keys({"C-u", "exit", "Enter"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return has(x, "HITL_EXIT=0"); }, 10s, &s)) << s;
  }
  std::filesystem::remove_all(state);
  board.signal(SIGINT);
  board.wait(10s);
}

}  // namespace
}  // namespace hitl
