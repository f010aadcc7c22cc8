// hitl doctor end to end: the emulated board (hitl target) and the simulator (hitl sim) on loopback,
// once healthy and once per fault `hitl target --fault NAME` injects; doctor must fail exactly the
// checks that fault implies (docs/doctor.md), and nothing on a healthy setup.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <map>
#include <set>
#include <sstream>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
using test::json_lines;

/// What each fault must make fail, and nothing else (the checks it implies, docs/doctor.md).
const std::map<std::string, std::set<std::string>>& implied_failures() {
  static const std::map<std::string, std::set<std::string>> m = {
      {"none", {}},
      {"no-actuators", {"actuators"}},
      {"wrong-flags", {"actuator-flags"}},
      {"wrong-cal-acc0-id", {"params-calibration", "arming"}},
      {"sys-hitl-0", {"params-system", "hil-mode"}},
      {"dsp-hitl-stalled", {"dsp-hitl", "estimator", "arming"}},
      {"ekf-not-converging", {"estimator", "arming"}},
      {"no-vio-listener", {"vio-odometry"}},
  };
  return m;
}

/// The emulated board and the simulator in lockstep at --speed 5, on free ports.
struct Rig {
  uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), vio = test::free_udp_port(),
           clients = test::free_udp_port();
  std::unique_ptr<test::Process> board, sim;

  explicit Rig(const std::string& fault) {
    std::vector<std::string> b{test::hitl_binary(), "--json", "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                               "--gcs-port", std::to_string(gcs), "--vio-port", std::to_string(vio), "--lockstep"};
    if (fault != "none") b.insert(b.end(), {"--fault", fault});
    board = std::make_unique<test::Process>(b);
    sim = std::make_unique<test::Process>(std::vector<std::string>{
        test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
        std::to_string(test::free_udp_port()), "--vio-port", std::to_string(vio), "--clients", std::to_string(clients),
        "--lockstep", "--speed", "5", "--duration", "600"});
  }
  ~Rig() {
    sim->signal(SIGINT);
    board->signal(SIGINT);
    sim->wait(10s);
    board->wait(10s);
  }

  /// Until the board has run `board_s` of (simulated) time and, unless `ready_by_s` passed, is ready to arm.
  bool wait_for_board(double board_s, double ready_by_s) {
    const auto end = std::chrono::steady_clock::now() + 90s;
    while (std::chrono::steady_clock::now() < end) {
      for (const auto& j : json_lines(board->out())) {
        if (j.value("type", "") != "status") continue;
        const double t = j.value("board_time_s", 0.0);
        if (t >= board_s && (j.value("estimator_ready", false) || t >= ready_by_s)) return true;
      }
      if (!board->running() || !sim->running()) return false;
      std::this_thread::sleep_for(200ms);
    }
    return false;
  }

  test::RunResult doctor() {
    std::vector<std::string> a{"--json", "doctor", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port",
                               std::to_string(test::free_udp_port()), "--session-port", std::to_string(clients), "--hil-port",
                               std::to_string(hil), "--vio-port", std::to_string(vio)};
    return test::run_hitl(a, 90s);
  }
};

class DoctorFault : public ::testing::TestWithParam<std::string> {};

TEST_P(DoctorFault, FailsExactlyTheChecksTheFaultImplies) {
  const std::string fault = GetParam();
  Rig rig(fault);
  ASSERT_TRUE(rig.board->wait_for_stderr("EMULATED", 20s)) << rig.board->err();
  if (fault != "none") {
    EXPECT_NE(rig.board->err().find("FAULTS INJECTED: " + fault), std::string::npos) << rig.board->err();
  }
  ASSERT_TRUE(rig.wait_for_board(10.0, 16.0)) << rig.board->err() << rig.sim->err();

  const auto r = rig.doctor();
  const auto lines = json_lines(r.out);
  ASSERT_FALSE(lines.empty()) << r.out << r.err;
  const auto& summary = lines.back();
  ASSERT_EQ(summary.value("type", ""), "summary") << r.out;

  std::set<std::string> failed;
  std::vector<std::string> order;
  for (const auto& j : lines) {
    if (j.value("type", "") != "check") continue;
    for (const char* key : {"check", "group", "result", "saw", "fix"}) EXPECT_TRUE(j.contains(key)) << key << " in " << j.dump();
    order.push_back(j["check"].get<std::string>());
    const std::string result = j["result"].get<std::string>();
    EXPECT_TRUE(result == "pass" || result == "warn" || result == "fail" || result == "skip") << j.dump();
    if (result == "fail") {
      failed.insert(j["check"].get<std::string>());
      EXPECT_TRUE(j["fix"].is_string() && !j["fix"].get<std::string>().empty()) << j.dump();
    }
  }
  EXPECT_EQ(order.size(), 30u) << r.out;
  EXPECT_EQ(order.front(), "route");
  EXPECT_EQ(order.back(), "px4-params");
  EXPECT_EQ(failed, implied_failures().at(fault)) << r.out << r.err;
  EXPECT_EQ(summary["failed"].get<std::size_t>(), failed.size());
  EXPECT_EQ(summary["ok"].get<bool>(), failed.empty());
  EXPECT_EQ(r.exit_code, failed.empty() ? 0 : 1) << r.err;

  // What a healthy loopback setup shows beyond "nothing failed": the board and the session seen.
  std::map<std::string, std::string> result;
  for (const auto& j : lines)
    if (j.value("type", "") == "check") result[j["check"].get<std::string>()] = j["result"].get<std::string>();
  EXPECT_EQ(result["heartbeat"], "pass");
  EXPECT_EQ(result["session"], "pass");
  EXPECT_EQ(result["route"], "skip");  // 127.0.0.1: no USB-Ethernet
  EXPECT_EQ(result["vio-server"], "skip");  // no adb
  if (fault == "none") {
    for (const char* c : {"ports", "hil-mode", "mavlink-instances", "actuators", "actuator-flags", "armed-state", "dsp-hitl",
                          "params-system", "params-calibration", "estimator", "arming", "vio-odometry"})
      EXPECT_EQ(result[c], "pass") << c << ": " << r.out;
  }
}

INSTANTIATE_TEST_SUITE_P(EachFault, DoctorFault,
                         ::testing::Values("none", "no-actuators", "wrong-flags", "wrong-cal-acc0-id", "sys-hitl-0",
                                           "dsp-hitl-stalled", "ekf-not-converging", "no-vio-listener"),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

TEST(DoctorE2E, NoBoardNoSessionHumanOutput) {
  const uint16_t gcs = test::free_udp_port(), clients = test::free_udp_port(), hil = test::free_udp_port(),
                 vio = test::free_udp_port();
  auto r = test::run_hitl({"doctor", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port",
                           std::to_string(test::free_udp_port()), "--session-port", std::to_string(clients), "--hil-port",
                           std::to_string(hil), "--vio-port", std::to_string(vio), "--timeout", "1"},
                          60s);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("[FAIL] HEARTBEAT from the board: no autopilot HEARTBEAT"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("         fix: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[FAIL] simulator session: no hitl sim session on 127.0.0.1:" + std::to_string(clients)),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[skip] dsp_hitl counters and rates: no link to the board"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[warn] HIL and VIO ports on this host"), std::string::npos) << r.out;  // nothing holds them
  EXPECT_NE(r.out.find("30 checks: 0 passed, 1 warned, 2 failed, 27 skipped"), std::string::npos) << r.out;
}

TEST(DoctorE2E, BadOptionsAreUsageErrors) {
  EXPECT_EQ(test::run_hitl({"doctor", "--listen", "0.1"}).exit_code, 2);
  EXPECT_EQ(test::run_hitl({"doctor", "--hil-port", "0"}).exit_code, 2);
  auto bad = test::run_hitl({"target", "--fault", "no-gps"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("'no-gps' is not a fault"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace hitl
