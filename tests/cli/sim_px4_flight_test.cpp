// Real PX4 flown by `hitl sim --px4` (ctest -L px4): HITL_PX4_DIR names a PX4 v1.16.0 SITL build or
// a PX4 tree with build/px4_sitl_default (scripts/px4-sitl.sh); without it every test here skips,
// saying so. The square at 1x and at --px4-speed 10 (done, a landing with one touchdown and no
// rebound, the tracking figures printed), two sessions at once, and no PX4 left behind by SIGKILL.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"

namespace hitl::test {
namespace {

using namespace std::chrono_literals;

class Px4Flight : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* dir = std::getenv("HITL_PX4_DIR");
    if (dir == nullptr || *dir == '\0')
      GTEST_SKIP() << "HITL_PX4_DIR is not set: these tests fly real PX4 SITL (build it with scripts/px4-sitl.sh TREE, "
                      "then HITL_PX4_DIR=TREE ctest -L px4)";
    px4_dir_ = dir;
  }

  /// `hitl --json sim --px4 DIR -t square.json` with `more`; the summary checked for a clean flight.
  std::vector<std::string> square_args(std::vector<std::string> more = {}) const {
    std::vector<std::string> args = {"--json", "sim", "--px4", px4_dir_, "--no-vio", "--clients", "0", "-t",
                                     std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json"};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }

  static void expect_clean_square(const RunResult& r, const char* what) {
    ASSERT_EQ(r.exit_code, 0) << what << "\n" << r.err;
    const auto j = last_json_line(r.out);
    ASSERT_TRUE(j.contains("trajectory")) << r.out;
    EXPECT_EQ(j["trajectory"]["state"], "DONE") << j.dump();
    EXPECT_EQ(j["landing"]["touchdowns"], 1) << j.dump();
    EXPECT_LT(j["landing"]["max_rebound_m"].get<double>(), 0.05) << j.dump();
    // PX4's Position mode follows the sticks with its own acceleration and jerk limits: the square
    // is flown within a couple of metres, not as tightly as the emulated board.
    EXPECT_LT(j["trajectory"]["max_m"].get<double>(), 4.0) << j.dump();
    std::printf("[ figures  ] %s: tracking RMS %.2f m, max %.2f m; touchdown %.2f m/s; %.1f s simulated in %.1f s\n", what,
                j["trajectory"]["rms_m"].get<double>(), j["trajectory"]["max_m"].get<double>(),
                j["landing"]["max_touchdown_speed_m_s"].get<double>(), j["sim_time_s"].get<double>(),
                j["wall_time_s"].get<double>());
  }

  std::string px4_dir_;
};

TEST_F(Px4Flight, SquareAtRealTime) { expect_clean_square(run_hitl(square_args(), 300s), "1x"); }

TEST_F(Px4Flight, SquareAtTenTimesRealTime) {
  expect_clean_square(run_hitl(square_args({"--px4-speed", "10"}), 300s), "--px4-speed 10");
}

TEST_F(Px4Flight, TwoSessionsAtOnceBothFly) {
  std::vector<std::string> a = {hitl_binary()}, b = {hitl_binary()};
  for (const auto& s : square_args({"--px4-speed", "2"})) {
    a.push_back(s);
    b.push_back(s);
  }
  Process first(a), second(b);
  const int code_a = first.wait(300s), code_b = second.wait(300s);
  expect_clean_square({code_a, first.out(), first.err()}, "first of two at 2x");
  expect_clean_square({code_b, second.out(), second.err()}, "second of two at 2x");
}

TEST_F(Px4Flight, ScenarioConditionsSeePx4sModeFromItsGcsInstance) {
  // PX4 SITL's simulator link sends one HEARTBEAT; the mode comes from PX4's GCS instance.
  const std::string scenario = temp_dir() + "/modes.json";
  {
    std::ofstream(scenario) << R"({"events": [{"id": "in-takeoff", "when": {"mode": "Takeoff"}, "fault": "imu-noise", "args": [1.5], "duration_s": 1},
                                              {"id": "in-land", "when": {"mode": "Land"}, "fault": "imu-noise", "args": [1.5], "duration_s": 1},
                                              {"id": "never", "when": {"mode": "Offboard"}, "fault": "imu-noise", "args": [1.5]}]})";
  }
  const auto r = run_hitl(square_args({"--px4-speed", "5", "--scenario", scenario}), 300s);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  ASSERT_EQ(j["faults"].size(), 2u) << j.dump();
  EXPECT_EQ(j["faults_not_started"], nlohmann::json::array({"never (imu-noise:1.5)"})) << j.dump();
}

TEST_F(Px4Flight, KillOfHitlLeavesNoPx4) {
  Process sim({hitl_binary(), "sim", "--px4", px4_dir_, "--no-vio", "--clients", "0"});
  ASSERT_TRUE(sim.wait_for_stderr("PX4 SITL connected", 60s)) << sim.err();
  std::smatch m;
  const std::string err = sim.err();
  ASSERT_TRUE(std::regex_search(err, m, std::regex("\\(pid ([0-9]+)\\)"))) << err;
  const int px4 = std::stoi(m[1]);
  sim.signal(SIGKILL);
  sim.wait(10s);
  const auto until = std::chrono::steady_clock::now() + 5s;
  auto alive = [px4] {
    std::ifstream stat("/proc/" + std::to_string(px4) + "/stat");
    std::string line;
    if (!std::getline(stat, line)) return false;
    const auto close = line.rfind(')');
    return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
  };
  while (alive() && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(50ms);
  EXPECT_FALSE(alive()) << "PX4 " << px4 << " outlived hitl's SIGKILL";
}

}  // namespace
}  // namespace hitl::test
