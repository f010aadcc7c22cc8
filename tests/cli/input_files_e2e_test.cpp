// Issue 19, files from outside through the real binary: endless or huge files, values past any
// physical limit, and options a user can get wrong give a named error quickly, never a hang.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/process.h"
#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

// Endless or huge files as inputs: a named error saying the limit, quickly (a 2 GB read before).
TEST(InputFilesE2E, EndlessFilesAreRefusedWithTheLimitNamed) {
  const std::string zero = "/dev/zero";
  const std::vector<std::vector<std::string>> commands = {
      {"sim", "-t", zero, "--duration", "1"},
      {"fly", "trajectory", zero},
      {"demo", "-t", zero},
      {"sim", "--vehicle", zero, "--duration", "1"},
      {"sim", "--world", zero, "--duration", "1"},
      {"--config", zero, "inspect", "--tlog", zero},
      {"params", "load", zero},
      {"--dialect", zero, "inspect", "--tlog", zero},
  };
  for (const auto& c : commands) {
    auto r = test::run_hitl(c, 30s);
    std::string line;
    for (const auto& a : c) line += a + " ";
    EXPECT_EQ(r.exit_code, 2) << line << r.err;
    EXPECT_NE(r.err.find("/dev/zero' is larger than"), std::string::npos) << line << r.err;
    EXPECT_NE(r.err.find("MiB, the limit for a"), std::string::npos) << line << r.err;
  }
}

TEST(InputFilesE2E, TrajectoryValuesBeyondPhysicalLimitsAreRefusedNamingTheKey) {
  const auto dir = test::temp_dir();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"({"waypoints":[{"t":0,"x":1e308,"y":0,"z":2}]})", "waypoints[0].x: must be within +-10000 m (got 1e+308)"},
      {R"({"waypoints":[{"t":0,"x":0,"y":0,"z":2},{"t":1e300,"x":0,"y":0,"z":2}]})", "waypoints[1].t: must be <= 86400 s"},
      {R"({"waypoints":[{"t":0,"x":0,"y":-2e4,"z":2}]})", "waypoints[0].y: must be within +-10000 m"},
      {R"({"waypoints":[{"t":0,"x":0,"y":0,"z":5000}]})", "waypoints[0].z: must be within +-1000 m"},
      {R"({"waypoints":[{"t":0,"x":0,"y":0,"z":2,"yaw":1e9}]})", "waypoints[0].yaw: must be within +-100 rad"},
  };
  int i = 0;
  for (const auto& [text, message] : cases) {
    const auto path = dir + "/t" + std::to_string(i++) + ".json";
    std::ofstream(path) << text;
    auto r = test::run_hitl({"sim", "-t", path, "--duration", "1"}, 30s);
    EXPECT_EQ(r.exit_code, 2) << text << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << text << r.err;
  }
}

// Found by the fuzzers: a number past a double's range (1e400) threw out of the JSON parser and
// aborted hitl (SIGABRT).
TEST(InputFilesE2E, NumbersPastADoublesRangeAreAnErrorNotAnAbort) {
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/t.json") << R"({"waypoints":[{"t":0,"x":1e400,"y":0,"z":2}]})";
  std::ofstream(dir + "/v.json") << R"({"mass_kg": 1e400})";
  std::ofstream(dir + "/w.json") << R"({"home": {"lat_deg": -1e400}})";
  for (const auto& c : std::vector<std::vector<std::string>>{{"sim", "-t", dir + "/t.json", "--duration", "1"},
                                                             {"sim", "--vehicle", dir + "/v.json", "--duration", "1"},
                                                             {"sim", "--world", dir + "/w.json", "--duration", "1"}}) {
    auto r = test::run_hitl(c, 30s);
    EXPECT_EQ(r.exit_code, 2) << c[2] << r.err;
    EXPECT_NE(r.err.find("number overflow"), std::string::npos) << c[2] << r.err;
  }
}

// Issue 34: scenario files that crashed or were accepted and never fired. Each is refused before
// anything runs, exit 2 (an input error), naming the file and the problem.
TEST(InputFilesE2E, HostileScenariosAreRefusedNotACrash) {
  const auto dir = test::temp_dir();
  // An event nested 70,000 arrays deep: SIGSEGV building the error text before.
  {
    std::ofstream deep(dir + "/deep.json");
    deep << R"({"events": [)" << std::string(70000, '[') << std::string(70000, ']') << "]}";
  }
  // 1,100 stacked motor:0,2 from t=0: multiplied to 2^1100 before.
  {
    std::ofstream stacked(dir + "/stacked.json");
    stacked << R"({"events": [)";
    for (int i = 0; i < 1100; ++i) stacked << (i ? "," : "") << R"({"at_s": 0, "fault": "motor", "args": [0, 2]})";
    stacked << "]}";
  }
  const std::string data = test::source_path("tests/data/hostile/");
  const std::pair<std::string, std::string> cases[] = {
      {dir + "/deep.json", "is nested deeper than 32 levels"},
      {data + "scenario-1e400.json", "number overflow"},
      {data + "scenario-cycle.json", "events 'a', 'b', 'c' wait on each other ('a' after 'c', 'b' after 'a', 'c' after 'b'): none would start"},
      {dir + "/stacked.json", "at most 64 faults can be active at once; 1100 could be at t=0 s"},
  };
  for (const auto& [path, message] : cases) {
    auto r = test::run_hitl({"sim", "--scenario", path, "--duration", "1"}, 30s);
    EXPECT_EQ(r.exit_code, 2) << path << r.err;
    EXPECT_NE(r.err.find("--scenario: scenario '" + path + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << path << r.err;
    EXPECT_LT(r.err.size(), 2000u) << "the message stays short: " << r.err.substr(0, 300);
  }
}

TEST(InputFilesE2E, NegativeSeedIsRefused) {
  auto r = test::run_hitl({"sim", "--seed", "-1", "--duration", "1"}, 30s);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--seed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("-1 is negative"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace hitl
