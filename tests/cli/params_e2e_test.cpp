// hitl params end to end against hitl target: directly, through a running hitl sim session,
// with no board, and with the direct port taken.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>

#include "engine/net/udp_endpoint.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

class ParamsE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    gcs_ = test::free_udp_port();
    hil_ = test::free_udp_port();
    local_ = test::free_udp_port();
    board_ = std::make_unique<test::Process>(std::vector<std::string>{
        test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil_), "--gcs-port",
        std::to_string(gcs_), "--vio-port", "0"});
    ASSERT_TRUE(board_->wait_for_stderr("EMULATED", 10s)) << board_->err();
  }
  void TearDown() override {
    board_->signal(SIGINT);
    board_->wait(10s);
  }
  /// hitl [--json] params ARGS..., directly to the board's GCS instance from our fixed local port.
  test::RunResult params(std::vector<std::string> args, bool json = false) {
    std::vector<std::string> a;
    if (json) a.push_back("--json");
    a.insert(a.end(), {"params", "-i", "127.0.0.1", "--port", std::to_string(gcs_), "--local-port", std::to_string(local_),
                       "--session-port", std::to_string(test::free_udp_port())});
    a.insert(a.end(), args.begin(), args.end());
    return test::run_hitl(a);
  }
  uint16_t gcs_ = 0, hil_ = 0, local_ = 0;
  std::unique_ptr<test::Process> board_;
};

TEST_F(ParamsE2E, ResetRepairsAPerturbedBoardAndDiffIsEmptyAfterwards) {
  EXPECT_EQ(params({"set", "SYS_HITL", "0"}).exit_code, 0);
  EXPECT_EQ(params({"set", "cal_acc0_id", "5"}).exit_code, 0);  // names in any case
  auto check = params({"check"});
  EXPECT_EQ(check.exit_code, 1);
  EXPECT_NE(check.out.find("FAIL SYS_HITL: board 0, HITL default 1  -> hitl params set SYS_HITL 1"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("PASS EKF2_GPS_CTRL"), std::string::npos);
  auto diff = params({"diff"}, true);
  EXPECT_EQ(diff.exit_code, 1);
  std::size_t wrong = 0;  // and the two this firmware lacks, listed with absent: true
  const auto differences = nlohmann::json::parse(diff.out)["differences"];
  for (const auto& row : differences) wrong += row["absent"].get<bool>() ? 0 : 1;
  EXPECT_EQ(wrong, 2u);
  auto dry = params({"reset", "--dry-run"});
  EXPECT_EQ(dry.exit_code, 0);
  EXPECT_NE(dry.out.find("would set CAL_ACC0_ID: 5 -> 1310988"), std::string::npos) << dry.out;
  auto reset = params({"reset"}, true);
  EXPECT_EQ(reset.exit_code, 0) << reset.err;
  const auto j = nlohmann::json::parse(reset.out);
  EXPECT_EQ(j["set"].size(), 2u);
  EXPECT_TRUE(j["failed"].empty());
  EXPECT_GT(j["unchanged"].size(), 40u);
  auto after = params({"diff"});
  EXPECT_EQ(after.exit_code, 0);
  EXPECT_NE(after.out.find("no differences"), std::string::npos);
  EXPECT_EQ(params({"check"}).exit_code, 0);
}

// PX4 v1.16 has no COM_ARM_EKF_POS or COM_ARM_EKF_VEL, and hitl target follows it: check, diff
// and reset report them as absent, with the firmware's version (AUTOPILOT_VERSION) and what
// replaces them, and pass unless --strict. A wrong value still fails.
TEST_F(ParamsE2E, ParametersThisFirmwareLacksAreAbsentNotWrong) {
  auto check = params({"check"});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("ABSENT COM_ARM_EKF_POS: this firmware (v1.16.0"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("ABSENT COM_ARM_EKF_VEL"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("PR #23411"), std::string::npos) << check.out;
  EXPECT_EQ(check.out.find("FAIL "), std::string::npos) << check.out;
  EXPECT_EQ(params({"check", "--strict"}).exit_code, 1);

  auto json = params({"check"}, true);
  EXPECT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_EQ(j["firmware"].get<std::string>().rfind("v1.16.0", 0), 0u) << json.out;
  ASSERT_EQ(j["absent"].size(), 2u) << json.out;
  EXPECT_EQ(j["absent"][0], "COM_ARM_EKF_POS");
  bool found = false;
  for (const auto& row : j["checks"]) {
    if (row["name"] != "COM_ARM_EKF_VEL") continue;
    found = true;
    EXPECT_TRUE(row["absent"].get<bool>());
    EXPECT_FALSE(row["ok"].get<bool>());
    EXPECT_TRUE(row["board"].is_null());
    EXPECT_NE(row["note"].get<std::string>().find("EKF2_GPS_V_GATE"), std::string::npos) << row;
  }
  EXPECT_TRUE(found);

  auto diff = params({"diff"});
  EXPECT_EQ(diff.exit_code, 0) << diff.out;
  EXPECT_NE(diff.out.find("no differences"), std::string::npos) << diff.out;
  EXPECT_EQ(params({"diff", "--strict"}).exit_code, 1);

  auto reset = params({"reset"}, true);
  EXPECT_EQ(reset.exit_code, 0) << reset.out << reset.err;
  const auto r = nlohmann::json::parse(reset.out);
  EXPECT_TRUE(r["failed"].empty()) << reset.out;
  ASSERT_EQ(r["absent"].size(), 2u) << reset.out;
  EXPECT_EQ(r["absent"][1]["name"], "COM_ARM_EKF_VEL");
  EXPECT_EQ(params({"reset", "--strict"}).exit_code, 1);
  auto text = params({"reset"});
  EXPECT_NE(text.out.find("ABSENT COM_ARM_EKF_POS"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(", 2 absent"), std::string::npos) << text.out;

  EXPECT_EQ(params({"set", "SYS_HITL", "0"}).exit_code, 0);
  EXPECT_EQ(params({"check"}).exit_code, 1);
}

TEST_F(ParamsE2E, ExportLoadRoundTripGetAndBadValues) {
  const auto file = test::temp_dir() + "/board.params";
  EXPECT_EQ(params({"set", "MPC_XY_P", "1.3"}).exit_code, 0);
  ASSERT_EQ(params({"export", file}).exit_code, 0);
  // A file that cannot be written is this machine's (unavailable): 2, naming the file.
  const auto unwritable = params({"export", "/nonexistent-hitl-dir/board.params"});
  EXPECT_EQ(unwritable.exit_code, 2) << unwritable.err;
  EXPECT_NE(unwritable.err.find("cannot write '/nonexistent-hitl-dir/board.params'"), std::string::npos) << unwritable.err;
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("1\t1\tMPC_XY_P\t1.3\t9"), std::string::npos);
  EXPECT_NE(text.find("1\t1\tCAL_ACC0_ID\t1310988\t6"), std::string::npos);
  EXPECT_EQ(params({"set", "MPC_XY_P", "0.5"}).exit_code, 0);
  auto load = params({"load", file});
  EXPECT_EQ(load.exit_code, 0) << load.out << load.err;
  EXPECT_NE(load.out.find("set MPC_XY_P: 0.5 -> 1.3"), std::string::npos) << load.out;
  auto get = params({"get", "MPC_XY_P"});
  EXPECT_EQ(get.out, "1.3\n");
  EXPECT_EQ(params({"set", "MPC_XY_P", "abc"}).exit_code, 2);
  EXPECT_EQ(params({"set", "MPC_XY_P", "1000"}).exit_code, 1);  // out of range: the board keeps its value
  EXPECT_EQ(params({"get", "NO_SUCH_PARAM"}).exit_code, 1);
  auto show = params({"show", "CAL_*_ID"}, true);
  EXPECT_EQ(nlohmann::json::parse(show.out)["params"].size(), 4u);  // ACC0, GYRO0, MAG0, BARO0
}

TEST_F(ParamsE2E, SetRefusesValuesOutOfTheParametersTypeAndLeavesTheBoardAlone) {
  // Issue 19: 99999999999 wrapped to 1215752191, 4294967297 to 1, exit 0.
  for (const char* bad : {"99999999999", "4294967297", "-2147483649", "1.5", "nan"}) {
    auto r = params({"set", "SYS_HITL", bad});
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.out;
    EXPECT_NE(r.err.find("SYS_HITL: value '" + std::string(bad) + "' is not a valid INT32 (an integer from -2147483648 to 2147483647)"),
              std::string::npos) << r.err;
  }
  for (const char* bad : {"1e39", "inf", "nan"}) {
    auto r = params({"set", "MPC_XY_P", bad});
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find("is not a valid REAL32"), std::string::npos) << r.err;
  }
  EXPECT_EQ(params({"get", "SYS_HITL"}).out, "1\n");
  EXPECT_EQ(params({"set", "SYS_HITL", "2147483647"}).exit_code, 0);  // the edge is a value
  EXPECT_EQ(params({"set", "SYS_HITL", "1"}).exit_code, 0);
}

TEST_F(ParamsE2E, WorksThroughARunningSimSession) {
  const uint16_t clients = test::free_udp_port();
  test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil_), "--local-port",
                     std::to_string(test::free_udp_port()), "--no-vio", "--clients", std::to_string(clients), "--duration", "30"});
  ASSERT_TRUE(sim.wait_for_stderr("clients on", 10s)) << sim.err();
  // No direct path given (a port nobody answers on): auto must go through the session.
  auto r = test::run_hitl({"params", "--session-port", std::to_string(clients), "-i", "127.0.0.1", "--port",
                           std::to_string(test::free_udp_port()), "--local-port", std::to_string(test::free_udp_port()),
                           "get", "SYS_HITL"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1\n");
  EXPECT_NE(r.err.find("through the session"), std::string::npos) << r.err;
  sim.signal(SIGINT);
  sim.wait(10s);
}

TEST(ParamsNoBoard, SaysWhatIsWrongAndExitsOne) {
  auto none = test::run_hitl({"params", "-i", "127.0.0.1", "--port", std::to_string(test::free_udp_port()), "--local-port",
                              std::to_string(test::free_udp_port()), "--session-port", std::to_string(test::free_udp_port()),
                              "--timeout", "1", "get", "SYS_HITL"});
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("no autopilot HEARTBEAT"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("answers only the first address"), std::string::npos);

  net::UdpEndpoint::Config c;
  c.bind_address = "0.0.0.0";
  auto holder = net::UdpEndpoint::open(c);
  ASSERT_TRUE(holder.ok());
  auto busy = test::run_hitl({"params", "--local-port", std::to_string(holder->local_address().port()), "--session-port",
                              std::to_string(test::free_udp_port()), "--timeout", "1", "show"});
  EXPECT_EQ(busy.exit_code, 1);
  EXPECT_NE(busy.err.find("hitl bridge"), std::string::npos) << busy.err;
}

}  // namespace
}  // namespace hitl
