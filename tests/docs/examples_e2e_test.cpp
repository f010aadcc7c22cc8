// docs/examples as a user runs them: every trajectory file parses with the real parser, the
// figure-eight and the yaw spin are flown by `hitl sim -t` against `hitl target` (their shape
// checked on the simulator's ground truth), the config file loads with `hitl --config` and takes
// effect, and phase1-check.sh passes, fails and refuses with the right exit codes.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <csignal>

#include "base/mavlink/messages.h"
#include "engine/faults/scenario.h"
#include "engine/vehicle/trajectory.h"
#include "tests/support/json_lines.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;

std::string example(const std::string& name) { return test::source_path("docs/examples/" + name); }

TEST(Examples, EveryTrajectoryFileParses) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("docs/examples"))) {
    if (entry.path().extension() != ".json") continue;
    names.push_back(entry.path().filename().string());
    const auto t = vehicle::Trajectory::load(entry.path().string());
    EXPECT_TRUE(static_cast<bool>(t)) << (t ? "" : t.error().message);
  }
  for (const char* expected : {"hover.json", "square.json", "figure-eight.json", "yaw-spin.json"})
    EXPECT_TRUE(test::contains(names, expected)) << expected;
}

TEST(Examples, EveryScenarioFileParses) {
  std::size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("docs/examples/scenarios"))) {
    ++n;
    const auto s = faults::load_scenario(entry.path().string());
    ASSERT_TRUE(static_cast<bool>(s)) << entry.path() << ": " << s.error().message;
    EXPECT_FALSE(s->empty()) << entry.path();
  }
  EXPECT_GE(n, 1U);
}

TEST(Examples, FigureEightAndYawSpinHaveTheirShape) {
  const auto eight = vehicle::Trajectory::load(example("figure-eight.json"));
  ASSERT_TRUE(static_cast<bool>(eight));
  // Two lobes: east of home, then west of it, crossing home in the middle; never much faster than 1 m/s.
  EXPECT_NEAR(eight->at(8).p_ENU_m[0], 4.0, 1e-9);
  EXPECT_NEAR(eight->at(16).p_ENU_m[0], 0.0, 1e-9);
  EXPECT_NEAR(eight->at(24).p_ENU_m[0], -4.0, 1e-9);
  for (double t = 0; t < eight->duration_s(); t += 0.5) {
    const auto v = eight->at(t).v_ENU_m_s;
    EXPECT_LT(std::hypot(v[0], v[1]), 1.1) << t;
  }
  const auto spin = vehicle::Trajectory::load(example("yaw-spin.json"));
  ASSERT_TRUE(static_cast<bool>(spin));
  // Each segment turns less than half a turn, so "the short way round" is the intended way.
  const auto& w = spin->waypoints();
  double turned_rad = 0;
  for (std::size_t i = 1; i < w.size(); ++i) {
    const double step = vehicle::wrap_pi(w[i].yaw_ENU_rad - w[i - 1].yaw_ENU_rad);
    EXPECT_LT(std::fabs(step), M_PI * 0.9);
    turned_rad += std::fabs(step);
  }
  EXPECT_NEAR(turned_rad, 4 * M_PI, 0.01);  // a full turn one way and back
  for (const auto& p : w) EXPECT_EQ(p.p_ENU_m, (std::array<double, 3>{0, 0, 2.5}));
}

/// What the simulator's ground truth (its ODOMETRY) showed during a flight.
struct TruthTrace {
  double min_east_m = 0, max_east_m = 0, min_north_m = 0, max_north_m = 0;
  double yaw_unwrapped_min_rad = 0, yaw_unwrapped_max_rad = 0;
  std::size_t samples = 0;
};

/// Flies `file` with `hitl sim -t` against `hitl target`, reading ground truth until the session ends.
nlohmann::json fly_example(const std::string& file, TruthTrace& trace) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), truth_port = test::free_udp_port(),
                 sim_local = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", "0", "--lockstep"});
  EXPECT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::MavlinkPeer truth(truth_port, 0);
  test::Process sim({test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil),
                     "--local-port", std::to_string(sim_local), "--vio-port", std::to_string(truth_port), "--vio-rate", "50",
                     "--clients", "0", "--lockstep", "--speed", "5", "-t", file});
  std::optional<std::array<double, 2>> home;
  std::optional<double> last_yaw;
  double unwrapped = 0;
  const auto deadline = std::chrono::steady_clock::now() + 240s;
  while (sim.running() && std::chrono::steady_clock::now() < deadline) {
    for (const auto& f : truth.receive_for(100ms)) {
      if (!f.is<msg::Odometry>()) continue;
      const auto o = f.as<msg::Odometry>();
      if (!home) home = std::array<double, 2>{o.x, o.y};
      const double north = o.x - (*home)[0], east = o.y - (*home)[1];
      trace.min_north_m = std::min(trace.min_north_m, north);
      trace.max_north_m = std::max(trace.max_north_m, north);
      trace.min_east_m = std::min(trace.min_east_m, east);
      trace.max_east_m = std::max(trace.max_east_m, east);
      // Yaw of FRD in NED from q (w, x, y, z); ENU yaw turns the other way, so its unwrapped range is the same.
      const double yaw = std::atan2(2.0 * (o.q[0] * o.q[3] + o.q[1] * o.q[2]), 1.0 - 2.0 * (o.q[2] * o.q[2] + o.q[3] * o.q[3]));
      if (last_yaw) unwrapped += vehicle::wrap_pi(yaw - *last_yaw);
      last_yaw = yaw;
      trace.yaw_unwrapped_min_rad = std::min(trace.yaw_unwrapped_min_rad, unwrapped);
      trace.yaw_unwrapped_max_rad = std::max(trace.yaw_unwrapped_max_rad, unwrapped);
      ++trace.samples;
    }
  }
  EXPECT_EQ(sim.wait(20s), 0) << sim.err();
  board.signal(SIGINT);
  EXPECT_EQ(board.wait(20s), 0) << board.err();
  const auto out = sim.out();
  if (out.empty()) {
    ADD_FAILURE() << "no summary from hitl sim; stderr:\n" << sim.err();
    return {};
  }
  return test::last_json_line(out);
}

TEST(ExampleFlights, FigureEight) {
  TruthTrace trace;
  const auto j = fly_example(example("figure-eight.json"), trace);
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["end"], "trajectory_done");
  EXPECT_EQ(j["trajectory"]["state"], "DONE");
  EXPECT_LT(j["trajectory"]["rms_m"].get<double>(), 1.0);
  EXPECT_LT(j["trajectory"]["max_m"].get<double>(), 2.0);
  EXPECT_FALSE(j["armed"].get<bool>());
  // Both lobes were flown: 4 m east and west of home, 2 m north and south.
  EXPECT_GT(trace.max_east_m, 3.0);
  EXPECT_LT(trace.min_east_m, -3.0);
  EXPECT_GT(trace.max_north_m, 1.2);
  EXPECT_LT(trace.min_north_m, -1.2);
  std::printf("figure-eight: rms %.2f m, max %.2f m; truth east %.2f..%.2f m, north %.2f..%.2f m\n",
              j["trajectory"]["rms_m"].get<double>(), j["trajectory"]["max_m"].get<double>(), trace.min_east_m,
              trace.max_east_m, trace.min_north_m, trace.max_north_m);
}

TEST(ExampleFlights, YawSpin) {
  TruthTrace trace;
  const auto j = fly_example(example("yaw-spin.json"), trace);
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["end"], "trajectory_done");
  EXPECT_EQ(j["trajectory"]["state"], "DONE");
  EXPECT_LT(j["trajectory"]["rms_m"].get<double>(), 0.6);  // it spins in place
  // A full turn one way, then back: the heading swept (nearly) 360 degrees.
  const double swept_deg = (trace.yaw_unwrapped_max_rad - trace.yaw_unwrapped_min_rad) * 180.0 / M_PI;
  EXPECT_GT(swept_deg, 320.0);
  EXPECT_LT(swept_deg, 400.0);
  std::printf("yaw-spin: rms %.2f m, max %.2f m; heading swept %.0f deg\n", j["trajectory"]["rms_m"].get<double>(),
              j["trajectory"]["max_m"].get<double>(), swept_deg);
}

TEST(ExampleConfig, LoadsAndTakesEffect) {
  const auto dir = test::temp_dir();
  const uint16_t hil = test::free_udp_port(), vio = test::free_udp_port(), local = test::free_udp_port();
  // The file's [sim] settings, with the board address and the recording overridden by flags.
  const auto sim = test::run_hitl({"--config", example("hitl.toml"), "--json", "sim", "-i", "127.0.0.1", "--hil-port",
                                   std::to_string(hil), "--local-port", std::to_string(local), "--vio-port",
                                   std::to_string(vio), "--clients", "0", "--duration", "2", "--speed", "0", "--record",
                                   dir + "/session.tlog"});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_NE(sim.err.find("GCS 127.0.0.1:14550"), std::string::npos) << sim.err;  // [sim] gcs, from the file
  EXPECT_NE(sim.err.find("to 127.0.0.1:" + std::to_string(hil)), std::string::npos) << sim.err;  // the flag won
  EXPECT_EQ(sim.err.find("192.168.101.2"), std::string::npos) << sim.err;
  ASSERT_TRUE(std::filesystem::exists(dir + "/session.tlog"));  // --record won over the file's

  // [inspect] tolerance = 10: the accepted band of an --expect rate is +-10 %.
  const auto inspect = test::run_hitl({"--config", example("hitl.toml"), "--json", "inspect", "--tlog", dir + "/session.tlog",
                                       "--expect", "HIL_SENSOR=250"});
  const auto j = test::last_json_line(inspect.out);
  ASSERT_TRUE(j.contains("expect")) << inspect.out << inspect.err;
  EXPECT_DOUBLE_EQ(j["expect"][0]["low_hz"].get<double>(), 225.0);
  EXPECT_DOUBLE_EQ(j["expect"][0]["high_hz"].get<double>(), 275.0);

  // A misspelt key is an error naming it.
  auto text = test::read_text(example("hitl.toml"));
  text.replace(text.find("vio-rate"), 8, "vio-rat");
  test::write_text(dir + "/bad.toml", text);
  const auto bad = test::run_hitl({"--config", dir + "/bad.toml", "sim", "--duration", "1"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("vio-rat"), std::string::npos) << bad.err;
}

class Phase1Check : public ::testing::Test {
 protected:
  /// Runs docs/examples/phase1-check.sh with hitl from the build.
  static test::RunResult run_script(std::vector<std::string> args, const std::string& hitl = test::hitl_binary()) {
    std::vector<std::string> argv{"/usr/bin/env", "HITL=" + hitl, "/bin/bash", example("phase1-check.sh")};
    argv.insert(argv.end(), args.begin(), args.end());
    return test::run_program(argv, 60s);
  }
};

TEST_F(Phase1Check, IsShellcheckClean) {
  if (test::find_program("shellcheck").empty()) GTEST_SKIP() << "shellcheck is not installed (scripts/install-deps.sh --test)";
  const auto r = test::run_program({"shellcheck", example("phase1-check.sh")});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST_F(Phase1Check, PassesWhileTheSimulatorSendsOdometry) {
  const uint16_t hil = test::free_udp_port(), vio = test::free_udp_port(), local = test::free_udp_port();
  test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
                     std::to_string(local), "--vio-port", std::to_string(vio), "--clients", "0", "--duration", "15"});
  ASSERT_TRUE(sim.wait_for_stderr("ODOMETRY to", 10s)) << sim.err();
  // A wider band than the default 5 %: the machine running the tests is shared and noisy.
  const auto r = run_script({"--port", std::to_string(vio), "--duration", "4", "--tolerance", "15"});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("Phase 1 PASS"), std::string::npos) << r.out << r.err;
  EXPECT_NE(r.out.find("ODOMETRY"), std::string::npos);
  sim.signal(SIGINT);
  sim.wait(20s);
}

TEST_F(Phase1Check, FailsWithExit1WhenNothingArrives) {
  const auto r = run_script({"--port", std::to_string(test::free_udp_port()), "--duration", "1"});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("Phase 1 FAIL"), std::string::npos) << r.err;
}

TEST_F(Phase1Check, RefusesBadUsageWithExit2) {
  EXPECT_EQ(run_script({"--bogus"}).exit_code, 2);
  EXPECT_EQ(run_script({"--port"}).exit_code, 2);
  const auto bad_rate = run_script({"--port", std::to_string(test::free_udp_port()), "--rate", "fast", "--duration", "1"});
  EXPECT_EQ(bad_rate.exit_code, 2) << bad_rate.out << bad_rate.err;
  const auto missing = run_script({}, "/nonexistent/hitl");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("not found"), std::string::npos) << missing.err;
  const auto help = run_script({"--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("Exit: 0"), std::string::npos);
}

}  // namespace
}  // namespace hitl
