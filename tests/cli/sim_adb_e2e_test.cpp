// hitl sim --adb end to end: the emulated board (hitl target) on loopback ports, the stand-in adb
// first on PATH, the real hitl-adb-relay it starts, and the closed loop through the tunnel.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <thread>

#include "tests/support/fake_adb.h"
#include "tests/support/json_lines.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(SimAdbE2E, ClosedLoopThroughTheTunnelArmsTheBoard) {
  const uint16_t hil = test::free_udp_port(), vio = test::free_udp_port(), gcs = test::free_udp_port(),
                 clients = test::free_udp_port();
  test::Process board({test::hitl_binary(), "--json", "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", std::to_string(vio), "--lockstep"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::FakeAdb fake({.relay_args = "--hil-port " + std::to_string(hil) + " --vio-port " + std::to_string(vio) + " --gcs-port " +
                                    std::to_string(gcs) + " --hil-source-port 0 --gcs-source-port 0"});
  test::Process sim({test::hitl_binary(), "--json", "sim", "--adb", "--local-port", std::to_string(test::free_udp_port()),
                     "--clients", std::to_string(clients), "--lockstep", "--speed", "5", "--duration", "300"});
  ASSERT_TRUE(sim.wait_for_stderr("clients on", 30s)) << sim.err();
  EXPECT_NE(sim.err().find("hitl sim: adb tunnel: hitl-adb-relay is not on the board; pushing"), std::string::npos) << sim.err();
  EXPECT_NE(sim.err().find("hitl sim: board FAKE0001 through adb forward tcp:" + std::to_string(fake.relay_port()) + " -> tcp:14590"),
            std::string::npos) << sim.err();

  // Arming goes through the session's client port, the tunnel's HIL channel and the relay: the board
  // answers once its estimator has converged on the sensors that came the same way.
  bool armed = false;
  std::string last;
  for (int i = 0; i < 60 && !armed; ++i) {
    auto r = test::run_hitl({"--json", "arm", "--session-port", std::to_string(clients), "-i", "127.0.0.1", "--port",
                             std::to_string(test::free_udp_port()), "--local-port", std::to_string(test::free_udp_port())});
    armed = r.exit_code == 0;
    last = r.out + r.err;
    if (!armed) std::this_thread::sleep_for(500ms);
  }
  EXPECT_TRUE(armed) << last;
  EXPECT_NE(last.find("through the session"), std::string::npos) << last;

  sim.signal(SIGINT);
  ASSERT_EQ(sim.wait(30s), 0) << sim.err();
  const auto s = test::last_json_line(sim.out());
  EXPECT_GT(s["received"]["HIL_ACTUATOR_CONTROLS"]["count"].get<uint64_t>(), 200u) << s.dump();
  EXPECT_GT(s["sent"]["HIL_SENSOR"]["count"].get<uint64_t>(), 1000u);
  ASSERT_TRUE(s.contains("adb")) << s.dump();
  const auto& a = s["adb"];
  EXPECT_EQ(a["serial"], "FAKE0001");
  EXPECT_EQ(a["forward_port"], fake.relay_port());
  EXPECT_TRUE(a["connected"].get<bool>());
  EXPECT_EQ(a["link_losses"], 0);
  EXPECT_FALSE(a["rtt_ms"].is_null());
  EXPECT_GT(a["channels"]["HIL"]["to_board"].get<uint64_t>(), 1000u);
  EXPECT_GT(a["channels"]["HIL"]["from_board"].get<uint64_t>(), 200u);
  EXPECT_GT(a["channels"]["VIO"]["to_board"].get<uint64_t>(), 1000u);

  board.signal(SIGINT);
  ASSERT_EQ(board.wait(20s), 0) << board.err();
  const auto b = test::last_json_line(board.out());
  EXPECT_GT(b["odometry_received"].get<uint64_t>(), 1000u) << b.dump();  // VIO came through the tunnel too

  // What hitl asked adb to do: find the board, forward, start (push) the relay, remove the forward at the end.
  int at = fake.find_call("devices");
  EXPECT_EQ(at, 0);
  at = fake.find_call("-s FAKE0001 forward tcp:0 tcp:14590", at);
  EXPECT_GT(at, 0);
  at = fake.find_call("-s FAKE0001 push " + std::string(HITL_ADB_RELAY_BINARY) + " /tmp/hitl-adb-relay", at);
  EXPECT_GT(at, 0);
  at = fake.find_call("-s FAKE0001 shell /tmp/hitl-adb-relay --daemon --port 14590", at);
  EXPECT_GT(at, 0);
  const auto calls = fake.calls();
  EXPECT_EQ(calls.back(), "-s FAKE0001 forward --remove tcp:" + std::to_string(fake.relay_port()));
  EXPECT_TRUE(fake.stop_relays());
}

TEST(SimAdbE2E, WithoutAdbItSaysWhichPackageToInstall) {
  test::NoAdbOnPath no_adb;
  auto r = test::run_hitl({"sim", "--adb", "--duration", "1", "--clients", "0"}, 30s);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("hitl sim: --adb: adb not found on PATH: install the Debian package adb (sudo apt-get install adb)"),
            std::string::npos) << r.err;
}

TEST(SimAdbE2E, NoBoardAttachedSaysToPlugItIn) {
  test::FakeAdb fake({.devices = ""});
  auto r = test::run_hitl({"sim", "--adb", "--duration", "1", "--clients", "0"}, 30s);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("hitl sim: --adb: no board attached to adb: plug in the VOXL2's USB-C cable"), std::string::npos) << r.err;
  // --adb-serial alone means --adb, and names the serial it did not find.
  auto serial = test::run_hitl({"sim", "--adb-serial", "M0197X", "--duration", "1", "--clients", "0"}, 30s);
  EXPECT_EQ(serial.exit_code, 1);
  EXPECT_NE(serial.err.find("--adb-serial M0197X: no such device attached (`adb devices` lists none)"), std::string::npos) << serial.err;
}

TEST(SimAdbE2E, AdbAndAnAddressForTheBoardAreExclusive) {
  auto r = test::run_hitl({"sim", "--adb", "-i", "192.168.101.2", "--duration", "1"}, 30s);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace hitl
