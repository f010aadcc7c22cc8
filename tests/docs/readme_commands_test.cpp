// The README's two commands, ./scripts/demo.sh and ./scripts/test.sh, run in both orders: the
// second always builds and runs the tests (and fails when none ran), and the demo never changes the
// test build. Full builds are too slow for CI, so the real scripts run in a copy of the tree with
// cmake and ctest replaced by stand-ins (tests/docs/stubs) that keep a build directory's cache
// the way cmake does and report what would be built and tested.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/tools.h"

namespace hitl {
namespace {

namespace fs = std::filesystem;

class ReadmeCommands : public ::testing::Test {
 protected:
  void SetUp() override {
    tree_ = test::temp_dir() + "/tree";
    fs::create_directories(tree_ + "/scripts");
    for (const char* script : {"demo.sh", "test.sh"})
      fs::copy_file(test::source_path(std::string("scripts/") + script), tree_ + "/scripts/" + script);
    // Dependencies are the machine's business, not this test's.
    test::write_text(tree_ + "/scripts/install-deps.sh", "#!/bin/sh\nexit 0\n");
    fs::permissions(tree_ + "/scripts/install-deps.sh", fs::perms::owner_all, fs::perm_options::add);
    log_ = tree_ + "/stub.log";
  }

  test::RunResult run(const std::string& script, const std::vector<std::string>& args = {}) {
    std::vector<std::string> argv{"/usr/bin/env",
                                  "PATH=" + test::source_path("tests/docs/stubs") + ":/usr/bin:/bin",
                                  "HITL_STUB_LOG=" + log_, "bash", tree_ + "/scripts/" + script};
    argv.insert(argv.end(), args.begin(), args.end());
    return test::run_program(argv, std::chrono::seconds(30));
  }

  std::string cache() { return test::read_text(tree_ + "/build/CMakeCache.txt"); }

  std::string tree_;
  std::string log_;
};

TEST_F(ReadmeCommands, DemoThenTestRunsEveryTest) {
  const auto demo = run("demo.sh");
  ASSERT_EQ(demo.exit_code, 0) << demo.out << demo.err;
  EXPECT_NE(demo.out.find("stub hitl (build): demo"), std::string::npos) << demo.out;
  const auto tests = run("test.sh");
  ASSERT_EQ(tests.exit_code, 0) << tests.out << tests.err;
  EXPECT_NE(tests.out.find("tests passed, 0 tests failed out of 3"), std::string::npos) << tests.out;
  EXPECT_EQ(tests.out.find("No tests were found"), std::string::npos) << tests.out;
}

TEST_F(ReadmeCommands, TestThenDemoLeavesTheTestBuildAlone) {
  const auto tests = run("test.sh");
  ASSERT_EQ(tests.exit_code, 0) << tests.out << tests.err;
  EXPECT_NE(tests.out.find("out of 3"), std::string::npos) << tests.out;
  const auto before = cache();
  const auto demo = run("demo.sh", {"--tui"});
  ASSERT_EQ(demo.exit_code, 0) << demo.out << demo.err;
  EXPECT_NE(demo.out.find("stub hitl (build): demo --tui"), std::string::npos) << demo.out;
  EXPECT_EQ(cache(), before) << "the demo changed the test build's options";
  const auto again = run("test.sh");
  ASSERT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("out of 3"), std::string::npos) << again.out;
}

TEST_F(ReadmeCommands, TestShAsksForTheTestsAndForAFailureWhenNoneRan) {
  ASSERT_EQ(run("test.sh").exit_code, 0);
  const auto log = test::read_text(log_);
  EXPECT_NE(log.find("-DHITL_BUILD_TESTS=ON"), std::string::npos) << log;
  // ctest exits non-zero when it finds no test, instead of "No tests were found!!!" and 0.
  const auto ctest_call = log.substr(log.find("ctest "));
  EXPECT_NE(ctest_call.find("--no-tests=error"), std::string::npos) << log;
}

}  // namespace
}  // namespace hitl
