// `hitl arm --wait S` (issue 18): a script arms a board that has just started; while the preflight
// checks are pending (EKF alignment, GPS) it says what it waits for and retries, and after S it
// fails with the last reason. Against `hitl target` and `hitl sim` on free loopback ports.
#include <gtest/gtest.h>

#include <csignal>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(ArmWaitE2E, RetriesWhilePreflightIsPendingThenArms) {
  const std::string hil = std::to_string(test::free_udp_port()), gcs = std::to_string(test::free_udp_port()),
                    clients = std::to_string(test::free_udp_port());
  test::Process board({test::hitl_binary(), "target", "--lockstep", "--bind", "127.0.0.1", "--hil-port", hil, "--gcs-port", gcs,
                       "--vio-port", "0"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::Process sim({test::hitl_binary(), "sim", "--lockstep", "--speed", "1", "-i", "127.0.0.1", "--hil-port", hil,
                     "--local-port", std::to_string(test::free_udp_port()), "--no-vio", "--clients", clients});
  ASSERT_TRUE(sim.wait_for_stderr("HIL_SENSOR", 10s)) << sim.err();
  const std::vector<std::string> link{"--session-port", clients, "-i", "127.0.0.1", "--port", gcs, "--local-port",
                                      std::to_string(test::free_udp_port())};
  auto arm = [&](const std::string& wait_s) {
    std::vector<std::string> args{"arm", "--wait", wait_s};
    args.insert(args.end(), link.begin(), link.end());
    return test::run_hitl(args, 120s);
  };
  // Just started: the estimator has not converged; a short wait ends with the board's reason.
  const auto early = arm("0.5");
  EXPECT_EQ(early.exit_code, 1) << early.out << early.err;
  EXPECT_NE((early.out + early.err).find("Preflight Fail"), std::string::npos) << early.out << early.err;
  // Waiting long enough: it says what it waits for, then arms.
  const auto patient = arm("90");
  EXPECT_EQ(patient.exit_code, 0) << patient.out << patient.err;
  EXPECT_NE(patient.out.find("armed"), std::string::npos) << patient.out;
  EXPECT_NE(patient.err.find("waiting for the board"), std::string::npos) << patient.err;
  sim.signal(SIGINT);
  sim.wait(20s);
  board.signal(SIGINT);
  board.wait(20s);
}

}  // namespace
}  // namespace hitl
