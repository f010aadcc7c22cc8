// hitl sim end to end, the session around the steps: bad input and number options refused with exit
// 2 and a clear line, a record write error said at once, Ctrl-C ending a slow-motion session, and
// clients routed to the board with telemetry routed back.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <fstream>
#include <thread>

#include "tests/cli/sim_board.h"

namespace hitl {
namespace {

using namespace sim_e2e;

TEST(SimE2E, BadInputExitsTwoWithAClearLine) {
  test::MavlinkPeer holder(0, 0);
  auto in_use = test::run_hitl({"sim", "--bind", "127.0.0.1", "--local-port", std::to_string(holder.endpoint().local_address().port()), "--clients", "0"});
  EXPECT_EQ(in_use.exit_code, 2);
  EXPECT_NE(in_use.err.find("already in use"), std::string::npos) << in_use.err;
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/v.json") << R"({"rotors": [{"time_constant_up_s": -1}]})";
  auto bad = test::run_hitl({"sim", "--vehicle", dir + "/v.json", "--clients", "0"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("time_constant_up_s"), std::string::npos) << bad.err;
  EXPECT_EQ(test::run_hitl({"sim", "--px4-sitl", "ftp:1"}).exit_code, 2);
  // The same port for the clients and the HIL link's local port: say so, not "another process".
  const auto same = std::to_string(test::free_udp_port());
  auto clash = test::run_hitl({"sim", "--bind", "127.0.0.1", "--local-port", same, "--clients", same, "--duration", "1"});
  EXPECT_EQ(clash.exit_code, 2);
  EXPECT_NE(clash.err.find("--clients " + same + " is also the --local-port"), std::string::npos) << clash.err;
  EXPECT_EQ(test::run_hitl({"sim", "--speed", "-1"}).exit_code, 2);
  // A number too large for a double (1e400) in a JSON file aborted the process (SIGABRT, an
  // uncaught nlohmann out_of_range) instead of a named error.
  std::ofstream(dir + "/big.json") << R"({"sensors": {"imu": {"accel_range_m_s2": 1e400}}})";
  std::ofstream(dir + "/bigw.json") << R"({"home": {"lat_deg": 1e400}})";
  std::ofstream(dir + "/bigt.json") << R"({"waypoints": [{"t": 0, "x": 1e400, "y": 0, "z": 2, "yaw": 0}]})";
  for (const auto& args : std::vector<std::vector<std::string>>{{"sim", "--vehicle", dir + "/big.json", "--clients", "0"},
                                                                {"sim", "--world", dir + "/bigw.json", "--clients", "0"},
                                                                {"sim", "-t", dir + "/bigt.json", "--clients", "0"}}) {
    auto big = test::run_hitl(args);
    EXPECT_EQ(big.exit_code, 2) << args[2] << ": " << big.err;
    EXPECT_NE(big.err.find("1e400"), std::string::npos) << big.err;
    EXPECT_EQ(big.err.find("terminate called"), std::string::npos) << big.err;
  }
}

TEST(SimE2E, RecordWriteErrorIsSaidAtOnceAndExitsOne) {
  // Issue 19: `sim --record /dev/full` exited 0 with nothing written.
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "60", "--no-vio", "--record", "/dev/full"}));
  EXPECT_TRUE(sim.wait_for_stderr("writing '/dev/full' failed: No space left on device", 10s)) << sim.err();
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(30s), 1) << sim.err();
  EXPECT_EQ(last_json(sim.out())["record_error"], "writing '/dev/full' failed: No space left on device");
}

TEST(SimE2E, CtrlCEndsASlowMotionSessionAtOnce) {
  // At --speed 0.001 a 4 ms step is 4 s of wall time; Ctrl-C used to wait for the step's deadline
  // (at --speed 1e-9: never, the sleep restarting on each signal), with no summary.
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "60", "--no-vio", "--speed", "1e-6"}));
  ASSERT_TRUE(sim.wait_for_stderr("Ctrl-C to stop", 10s)) << sim.err();
  std::this_thread::sleep_for(300ms);
  const auto t0 = std::chrono::steady_clock::now();
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(5s), 0) << sim.err();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
  EXPECT_EQ(last_json(sim.out())["end"], "stopped") << sim.out();
}

TEST(SimE2E, NumberOptionsRefuseNanInfAndAbsurdValuesPlainly) {
  // Issue 19: --actuator-timeout nan disabled the motor-stop failsafe; --lockstep-timeout nan was taken.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--actuator-timeout", "nan"}, "--actuator-timeout: nan is not a finite number"},
      {{"--lockstep-timeout", "nan"}, "--lockstep-timeout: nan is not a finite number"},
      {{"--actuator-timeout", "inf"}, "--actuator-timeout: inf is not a finite number"},
      {{"--duration", "1e999"}, "--duration: 1e999 is not a finite number"},
      {{"--speed", "-1"}, "--speed: -1 is below 0"},
      {{"--truth-rate", "1e12"}, "--truth-rate: 1e12 is too large (at most 1e+09 in size)"},
      {{"--vio-rate", "0"}, "--vio-rate: 0 is not greater than 0"},
      {{"--seed", "-1"}, "--seed: -1 is negative; give 0 or more"},
  };
  for (const auto& [args, words] : cases) {
    std::vector<std::string> a{"sim", "--clients", "0"};
    a.insert(a.end(), args.begin(), args.end());
    const auto r = test::run_hitl(a, 20s);
    EXPECT_EQ(r.exit_code, 2) << args[0] << " " << args[1];
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("17976931348623157"), std::string::npos) << r.err;  // no DBL_MAX in words
  }
}

TEST(SimE2E, RoutesClientsToTheBoardAndTelemetryBack) {
  Board board;
  const uint16_t clients_port = test::free_udp_port();
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  auto args = board.sim_args({"--duration", "3", "--no-vio"});
  *(std::find(args.begin(), args.end(), "--clients") + 1) = std::to_string(clients_port);
  Process sim(args);
  std::this_thread::sleep_for(500ms);
  test::MavlinkPeer client(0, clients_port, 255, 190);
  msg::CommandLong cmd;
  cmd.command = 400;  // MAV_CMD_COMPONENT_ARM_DISARM
  cmd.param1 = 1;
  client.send(cmd);
  std::this_thread::sleep_for(300ms);
  bool board_got_command = false;
  for (const auto& f : board.frames()) board_got_command |= f.is<msg::CommandLong>() && f.sysid == 255;
  EXPECT_TRUE(board_got_command);
  board.peer().send(msg::Attitude{});
  const auto got = client.receive_for(500ms);
  bool client_got_attitude = false, client_got_hil = false;
  for (const auto& f : got) {
    client_got_attitude |= f.is<msg::Attitude>();
    client_got_hil |= f.is<msg::HilSensor>() || f.is<msg::HilGps>();
  }
  EXPECT_TRUE(client_got_attitude);
  EXPECT_FALSE(client_got_hil);
  EXPECT_EQ(sim.wait(30s), 0);
}

}  // namespace
}  // namespace hitl
