// Mistakes get help (issue 18): "did you mean" for commands and options, range errors in plain
// numbers, a config file's error with its file, line and the word TOML, --help without the
// parser's internals. All exit 2 (bad usage).
#include <gtest/gtest.h>

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

TEST(Mistakes, HelpWithoutParserInternals) {
  const auto r = test::run_hitl({"sim", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* internal : {"ENUM:", "INT in [", "->1"}) EXPECT_EQ(r.out.find(internal), std::string::npos) << internal;
  EXPECT_NE(r.out.find("--trajectory-mode attitude|velocity=velocity"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace hitl
