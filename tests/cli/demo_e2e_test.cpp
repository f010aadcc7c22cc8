// hitl demo: the README's first command flies the square on an emulated board and reports.
#include <gtest/gtest.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>
#include <nlohmann/json.hpp>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

TEST(DemoE2E, FliesTheSquareAndReports) {
  auto r = test::run_hitl({"--json", "demo"}, std::chrono::seconds(240));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = test::last_json_line(r.out);
  EXPECT_EQ(j["type"], "summary");
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_EQ(j["trajectory"]["state"], "DONE");
  // Against truth, flying on truth: measured RMS 0.34 m, max 0.81 m.
  EXPECT_LT(j["trajectory"]["rms_m"].get<double>(), 0.6);
  // Rates per simulated second: the spec's table.
  EXPECT_NEAR(j["rates_hz"]["HIL_SENSOR"].get<double>(), 250.0, 5.0);
  EXPECT_NEAR(j["rates_hz"]["HIL_GPS"].get<double>(), 30.0, 2.0);
  EXPECT_NEAR(j["rates_hz"]["ODOMETRY"].get<double>(), 250.0, 5.0);
  EXPECT_GT(j["rates_hz"]["HIL_ACTUATOR_CONTROLS"].get<double>(), 200.0);
  // The board's estimate against the simulator's truth reached the report.
  EXPECT_GT(j["estimate_error"]["position_samples"].get<uint64_t>(), 10u);
  EXPECT_LT(j["estimate_error"]["horizontal_rms_m"].get<double>(), 2.0);
  EXPECT_EQ(j["board"]["malformed"], 0);
}

// Stopped before it flew, the demo has measured nothing: it says n/a (JSON: null), not zeros.
TEST(DemoE2E, StoppedEarlyReportsNotApplicableNotZeros) {
  test::Process demo({test::hitl_binary(), "demo", "--speed", "1"});
  ASSERT_TRUE(demo.wait_for_stderr("Ctrl-C stops everything", std::chrono::seconds(20))) << demo.err();
  demo.signal(SIGINT);
  EXPECT_EQ(demo.wait(std::chrono::seconds(30)), 1) << demo.err();
  const std::string out = demo.out();
  EXPECT_NE(out.find("demo did not finish"), std::string::npos) << out;
  EXPECT_NE(out.find("tracking error against truth   RMS n/a, max n/a (0 samples)"), std::string::npos) << out;
  EXPECT_NE(out.find("horizontal RMS n/a"), std::string::npos) << out;
  EXPECT_EQ(out.find("RMS 0.00 m"), std::string::npos) << out;
}

// Each demo under $TMPDIR leaves its folder (its page is there); the older ones beyond the newest 5
// of this user go, and nothing else in $TMPDIR is touched.
TEST(DemoE2E, KeepsTheNewestFiveDemoFolders) {
  namespace fs = std::filesystem;
  const fs::path tmp = test::temp_dir();
  for (int i = 0; i < 6; ++i) {
    const fs::path old = tmp / ("hitl-demo-old00" + std::to_string(i));
    fs::create_directories(old);
    std::ofstream(old / "demo.tlog") << "x";
    fs::last_write_time(old, fs::file_time_type::clock::now() - std::chrono::hours(10 - i));  // old000 the oldest
  }
  fs::create_directories(tmp / "hitl-demo-mine-not");  // not a demo's name
  std::ofstream(tmp / "hitl-demo-abcdef") << "a file, not a folder";
  const char* before = std::getenv("TMPDIR");
  const std::string saved = before ? before : "";
  ::setenv("TMPDIR", tmp.c_str(), 1);
  test::Process demo({test::hitl_binary(), "demo", "--speed", "1"});
  if (saved.empty()) ::unsetenv("TMPDIR");
  else ::setenv("TMPDIR", saved.c_str(), 1);
  ASSERT_TRUE(demo.wait_for_stderr("Ctrl-C stops everything", std::chrono::seconds(20))) << demo.err();
  demo.signal(SIGINT);
  demo.wait(std::chrono::seconds(30));
  EXPECT_NE(demo.err().find("removed 2 older demo folders under " + tmp.string()), std::string::npos) << demo.err();
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(tmp)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_FALSE(fs::exists(tmp / "hitl-demo-old000"));
  EXPECT_FALSE(fs::exists(tmp / "hitl-demo-old001"));
  for (const char* kept : {"hitl-demo-old002", "hitl-demo-old005", "hitl-demo-mine-not", "hitl-demo-abcdef"})
    EXPECT_TRUE(fs::exists(tmp / kept)) << kept;
  EXPECT_EQ(left.size(), 7u);  // 4 old ones and the new demo's folder, and the two that are not demo folders
}

TEST(DemoE2E, ABadTrajectoryFileIsRefused) {
  const auto dir = test::temp_dir();
  const std::string bad = dir + "/bad.json";
  FILE* f = std::fopen(bad.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("{\"waypoints\": [{\"t\": 0, \"x\": 0}]}", f);
  std::fclose(f);
  auto r = test::run_hitl({"demo", "-t", bad});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("waypoints[0]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace hitl
