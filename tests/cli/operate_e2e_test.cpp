// hitl arm / disarm / shell end to end against hitl target (and hitl sim for a flyable board).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>

#include "tests/support/json_lines.h"
#include "tests/support/lockstep_session.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(OperateE2E, ArmDeniedWithTheReasonThenArmedAndDisarmedShellAnswers) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port(),
                 clients = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", "0", "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  auto direct = [&](std::vector<std::string> args) {
    std::vector<std::string> a{"--json"};
    a.insert(a.end(), args.begin(), args.end());
    a.insert(a.end(), {"-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port", std::to_string(local),
                       "--session-port", std::to_string(clients)});
    return test::run_hitl(a);
  };
  // No simulator yet: no sensor data, so arming is refused and the board says why.
  auto denied = direct({"arm"});
  EXPECT_EQ(denied.exit_code, 1);
  const auto d = nlohmann::json::parse(denied.out);
  EXPECT_FALSE(d["ok"].get<bool>());
  EXPECT_NE(d["reason"].get<std::string>().find("Preflight Fail"), std::string::npos) << denied.out;

  auto shell = direct({"shell", "-c", "qshell dsp_hitl status"});
  EXPECT_EQ(shell.exit_code, 0) << shell.err;
  EXPECT_NE(nlohmann::json::parse(shell.out.substr(0, shell.out.find('\n')))["output"].get<std::string>().find("=== IMU Section ==="), std::string::npos);

  // With the simulator the estimator converges; the direct link keeps working beside the session.
  test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
                     std::to_string(test::free_udp_port()), "--no-vio", "--clients", std::to_string(clients), "--lockstep",
                     "--speed", "5", "--duration", "200"});
  bool armed = false;
  for (int i = 0; i < 30 && !armed; ++i) {  // the estimator needs ~6 s of simulated time
    auto r = direct({"arm"});
    armed = r.exit_code == 0;
    if (!armed) std::this_thread::sleep_for(300ms);
  }
  EXPECT_TRUE(armed);
  auto disarm = direct({"disarm"});
  EXPECT_EQ(disarm.exit_code, 0) << disarm.out << disarm.err;

  // Fly: arm, take off to 3 m, hold, land; each waits for the outcome.
  ASSERT_EQ(direct({"arm"}).exit_code, 0);
  auto takeoff = direct({"fly", "takeoff", "--alt", "3"});
  ASSERT_EQ(takeoff.exit_code, 0) << takeoff.out << takeoff.err;
  const auto t = nlohmann::json::parse(takeoff.out);
  EXPECT_GE(t["altitude_m"].get<double>(), 2.7);
  EXPECT_EQ(t["target_m"], 3.0);
  auto hold = direct({"fly", "hold"});
  EXPECT_EQ(hold.exit_code, 0) << hold.out;
  auto land = direct({"fly", "land"});
  EXPECT_EQ(land.exit_code, 0) << land.out << land.err;
  EXPECT_EQ(nlohmann::json::parse(land.out)["message"], "landed and disarmed");
  // Disarmed on the ground: takeoff is refused and says so.
  auto refused = direct({"fly", "takeoff"});
  EXPECT_EQ(refused.exit_code, 1);
  sim.signal(SIGINT);
  board.signal(SIGINT);
  sim.wait(10s);
  board.wait(10s);
}

// hitl shell -c exits with what the board's command returned: PX4's shell prints
// "Command 'NAME' failed, returned N." for a non-zero return (hitl target as PX4's pxh does).
TEST(OperateE2E, ShellExitStatusFollowsTheBoardsCommand) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port(),
                 clients = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", "0", "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  auto shell = [&](std::vector<std::string> args) {
    std::vector<std::string> a{"shell"};
    a.insert(a.end(), args.begin(), args.end());
    a.insert(a.end(), {"-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port", std::to_string(local),
                       "--session-port", std::to_string(clients)});
    return test::run_hitl(a);
  };
  auto running = shell({"-c", "dsp_hitl status"});
  EXPECT_EQ(running.exit_code, 0) << running.out << running.err;
  EXPECT_NE(running.out.find("Running: yes"), std::string::npos) << running.out;

  auto stop = shell({"-c", "dsp_hitl stop"});
  EXPECT_EQ(stop.exit_code, 0) << stop.out << stop.err;
  // Stopped: status prints "Running: no" and returns 1, as target/px4's module does on PX4.
  auto stopped = shell({"-c", "dsp_hitl status"});
  EXPECT_EQ(stopped.exit_code, 1) << stopped.out << stopped.err;
  EXPECT_NE(stopped.out.find("Running: no"), std::string::npos) << stopped.out;
  EXPECT_NE(stopped.out.find("Command 'dsp_hitl' failed, returned 1."), std::string::npos) << stopped.out;
  EXPECT_NE(stopped.err.find("'dsp_hitl status' returned 1 on the board"), std::string::npos) << stopped.err;
  // Through qshell the failure is qshell's (it passes the DSP command's return on).
  auto qshell = shell({"-c", "qshell dsp_hitl status"});
  EXPECT_EQ(qshell.exit_code, 1) << qshell.out << qshell.err;
  EXPECT_NE(qshell.out.find("Command 'qshell' failed, returned 1."), std::string::npos) << qshell.out;
  // --json: the status with the output, then the one summary.
  auto json = shell({"--json", "-c", "dsp_hitl status"});
  EXPECT_EQ(json.exit_code, 1) << json.err;
  const auto j = nlohmann::json::parse(json.out.substr(0, json.out.find('\n')));
  EXPECT_EQ(j["type"], "shell");
  EXPECT_EQ(j["status"], 1);
  EXPECT_FALSE(j["ok"].get<bool>());
  const auto summary = test::last_json_line(json.out);
  EXPECT_EQ(summary["type"], "summary");
  EXPECT_EQ(summary["command"], "shell");
  EXPECT_EQ(summary["commands"], 1);
  EXPECT_EQ(summary["failed"], 1);
  EXPECT_FALSE(summary["ok"].get<bool>());
  // --ignore-status: the old behaviour, exit 0 whatever the command returned.
  auto ignored = shell({"--ignore-status", "-c", "dsp_hitl status"});
  EXPECT_EQ(ignored.exit_code, 0) << ignored.err;
  EXPECT_NE(ignored.out.find("Running: no"), std::string::npos) << ignored.out;
  // A command the board does not have.
  auto unknown = shell({"-c", "no_such_command"});
  EXPECT_EQ(unknown.exit_code, 1) << unknown.out << unknown.err;
  // A command the board has, used wrongly, fails as PX4's module does (usage, return 1), never as
  // "nsh: dsp_hitl: command not found" (which said dsp_hitl was missing after `dsp_hitl stop; ...`).
  auto two = shell({"-c", "dsp_hitl stop; dsp_hitl status"});
  EXPECT_EQ(two.exit_code, 1) << two.out << two.err;
  EXPECT_EQ(two.out.find("command not found"), std::string::npos) << two.out;
  EXPECT_NE(two.out.find("Command 'dsp_hitl' failed, returned 1."), std::string::npos) << two.out;
  auto bad_param = shell({"-c", "param set NO_SUCH_PARAM 1"});
  EXPECT_EQ(bad_param.exit_code, 1) << bad_param.out << bad_param.err;
  EXPECT_NE(bad_param.out.find("Command 'param' failed, returned 1."), std::string::npos) << bad_param.out;

  auto start = shell({"-c", "dsp_hitl start"});
  EXPECT_EQ(start.exit_code, 0) << start.out << start.err;
  auto again = shell({"-c", "dsp_hitl status"});
  EXPECT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("Running: yes"), std::string::npos) << again.out;
  board.signal(SIGINT);
  board.wait(10s);
}

TEST(OperateE2E, FlyTrajectoryFromTheHostThroughTheSession) {
  test::LockstepSessionWithClients session;
  ASSERT_EQ(session.failure(), "");
  auto r = test::run_hitl(session.fly({"trajectory", std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json"}),
                          std::chrono::seconds(120));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["state"], "DONE");
  // Against the board's own estimate (what the pilot flies on): measured RMS 0.37 m, max 0.82 m.
  EXPECT_LT(j["rms_m"].get<double>(), 0.6);
  EXPECT_LT(j["max_m"].get<double>(), 1.5);
  EXPECT_GT(j["trace"].size(), 100u);
  EXPECT_NE(r.err.find("through the session"), std::string::npos);
  // Against the simulator's truth (ODOMETRY the session sends its clients): the board's estimation
  // error comes on top (GPS-grade, a few decimetres). Measured RMS 0.40 m, max 0.97 m.
  EXPECT_GT(j["truth_samples"].get<uint64_t>(), 100u);
  EXPECT_LT(j["truth_rms_m"].get<double>(), 1.0);
  EXPECT_LT(j["truth_max_m"].get<double>(), 2.0);
  EXPECT_TRUE(j["trace"][0].contains("truth_p_enu_m"));

  // Attitude mode: Stabilized, the pilot closes position and velocity itself (measured: estimate
  // RMS 0.26 m, max 0.62 m; truth RMS 0.44 m, max 0.92 m).
  auto a = test::run_hitl(
      session.fly({"trajectory", "--mode", "attitude", std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json"}),
      std::chrono::seconds(120));
  EXPECT_EQ(a.exit_code, 0) << a.out << a.err;
  const auto ja = nlohmann::json::parse(a.out);
  EXPECT_EQ(ja["state"], "DONE");
  EXPECT_EQ(ja["mode"], "attitude");
  EXPECT_NE(a.err.find("Stabilized mode"), std::string::npos) << a.err;
  EXPECT_LT(ja["rms_m"].get<double>(), 0.6);
  EXPECT_LT(ja["truth_rms_m"].get<double>(), 1.0);
  // A bad file: refused before anything is sent.
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/bad.json") << R"({"waypoints": [{"t": 0, "x": 0, "y": 0}]})";
  auto bad = test::run_hitl({"fly", "--session-port", std::to_string(session.client_port()), "trajectory", dir + "/bad.json"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("waypoints[0].z: missing"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace hitl
