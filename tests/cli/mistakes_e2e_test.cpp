// Mistakes get help (issue 18): "did you mean" for commands and options, range errors in plain
// numbers, a config file's error with its file, line and the word TOML, --help without the
// parser's internals. All exit 2 (bad usage).
#include <gtest/gtest.h>

#include <csignal>
#include <fstream>

#include "tests/support/process.h"

namespace hitl {
namespace {

void says(const std::vector<std::string>& args, const std::string& expected) {
  const auto r = test::run_hitl(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
}

TEST(Mistakes, DidYouMean) {
  says({"simm"}, "hitl: unknown command 'simm'; did you mean 'sim'?");
  says({"fly", "takeof"}, "hitl fly: unknown command 'takeof'; did you mean 'takeoff'?");
  says({"sim", "--lockstpe"}, "hitl sim: unknown option '--lockstpe'; did you mean '--lockstep'?");
  says({"--jsn", "sim"}, "did you mean '--json'?");
}

TEST(Mistakes, DidYouMeanForParameterNamesFromTheBoardsList) {
  using namespace std::chrono_literals;
  const std::string gcs = std::to_string(test::free_udp_port()), local = std::to_string(test::free_udp_port());
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(test::free_udp_port()),
                       "--gcs-port", gcs, "--vio-port", "0"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  const std::vector<std::string> link{"-i", "127.0.0.1", "--port", gcs, "--local-port", local, "--session-port", std::to_string(test::free_udp_port())};
  auto params = [&](std::vector<std::string> args) {
    args.insert(args.begin(), "params");
    args.insert(args.end(), link.begin(), link.end());
    return test::run_hitl(args, 60s);
  };
  const auto set = params({"set", "SYS_HITLL", "1"});
  EXPECT_EQ(set.exit_code, 1) << set.err;
  EXPECT_NE(set.err.find("the board has no parameter SYS_HITLL"), std::string::npos) << set.err;
  EXPECT_NE(set.err.find("did you mean 'SYS_HITL'?"), std::string::npos) << set.err;
  const auto get = params({"get", "mpc_xy_pp"});  // any case, as the board's names are upper case
  EXPECT_NE(get.err.find("did you mean 'MPC_XY_P'?"), std::string::npos) << get.err;
  const auto far = params({"get", "XYZZY_FOO"});  // nothing close: no guess, where to look instead
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
  EXPECT_NE(far.err.find("hitl params show"), std::string::npos) << far.err;
  board.signal(SIGINT);
  board.wait(10s);
}

TEST(Mistakes, AnOptionsValueIsNamedOnce) {
  const auto r = test::run_hitl({"target", "--fault", "bogus"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("hitl target: --fault: 'bogus' is not a fault this board can inject"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("--fault: --fault"), std::string::npos) << r.err;
}

TEST(Mistakes, RangesInPlainNumbers) {
  says({"sim", "--speed", "1e400"}, "--speed: 1e400 is not a finite number");
  says({"inspect", "--port", "70000"}, "--port: 70000 is above 65535");
  const auto r = test::run_hitl({"sim", "--speed", "-1"});
  EXPECT_EQ(r.err.find("179769313486"), std::string::npos) << r.err;  // no DBL_MAX written out
}

TEST(Mistakes, ConfigErrorsNameFileLineAndToml) {
  const std::string file = test::temp_dir() + "/hitl.toml";
  std::ofstream(file) << "# a board\n[sim]\nspeeed = 2\n";
  says({"--config", file, "sim"}, file + ":3: unknown key 'speeed' in [sim]; did you mean 'speed'?");
  says({"--config", file, "sim"}, "TOML");
}

TEST(Mistakes, NoCommandListsTheCommands) {
  // `hitl` or `hitl params` alone: the commands there, each with what it does, as git does.
  says({}, "hitl: a command is needed:");
  says({}, "  sim ");
  says({}, "  doctor ");
  says({"params"}, "hitl params: a command is needed:");
  says({"params"}, "  reset ");
  says({"fly"}, "  takeoff ");
  says({"board"}, "hitl board: a command is needed:");
}

TEST(Mistakes, HelpWithoutParserInternals) {
  const auto r = test::run_hitl({"sim", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  // Issue 36: nor CLI11's type names and its "=DEFAULT Excludes: ..." after them.
  for (const char* internal : {"ENUM:", "INT in [", "->1", " UINT", " TEXT", " FLOAT", ":POSITIVE", "Excludes:", "=14560"})
    EXPECT_EQ(r.out.find(internal), std::string::npos) << internal << " in:\n" << r.out;
  EXPECT_NE(r.out.find("--trajectory-mode attitude|velocity"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--hil-port, --mavlink-udp-remote-port HIL_PORT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Default: 14560."), std::string::npos) << r.out;
}

}  // namespace
}  // namespace hitl
