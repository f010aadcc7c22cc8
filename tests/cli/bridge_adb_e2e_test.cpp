// hitl bridge --adb end to end: the emulated board (hitl target) on loopback ports, the stand-in adb
// first on PATH, the real hitl-adb-relay it starts, and a command through the bridge's client port,
// the tunnel's GCS channel and the relay to the board's GCS instance.
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

TEST(BridgeAdbE2E, CommandsReachTheBoardThroughTheTunnelsGcsChannel) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), clients = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
                       std::to_string(gcs), "--vio-port", "0"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  test::FakeAdb fake({.relay_args = "--hil-port " + std::to_string(hil) + " --gcs-port " + std::to_string(gcs) +
                                    " --hil-source-port 0 --gcs-source-port 0"});
  test::Process bridge({test::hitl_binary(), "--json", "bridge", "--adb", "--local-port", std::to_string(test::free_udp_port()),
                        "--clients", std::to_string(clients), "--duration", "120"});
  ASSERT_TRUE(bridge.wait_for_stderr("clients on", 30s)) << bridge.err();
  EXPECT_NE(bridge.err().find("hitl bridge: board FAKE0001 through adb forward tcp:" + std::to_string(fake.relay_port())),
            std::string::npos) << bridge.err();

  std::string last, value;
  bool got = false;
  for (int i = 0; i < 20 && !got; ++i) {
    auto r = test::run_hitl({"params", "get", "SYS_HITL", "--session-port", std::to_string(clients), "-i", "127.0.0.1",
                             "--port", std::to_string(test::free_udp_port())});
    got = r.exit_code == 0;
    last = r.out + r.err;
    value = r.out;
    if (!got) std::this_thread::sleep_for(500ms);
  }
  ASSERT_TRUE(got) << last << bridge.err();
  EXPECT_EQ(value, "1\n") << last;  // the emulated board runs the HITL set
  EXPECT_NE(last.find("through the session"), std::string::npos) << last;

  bridge.signal(SIGINT);
  ASSERT_EQ(bridge.wait(30s), 0) << bridge.err();
  const auto s = test::last_json_line(bridge.out());
  ASSERT_EQ(s.value("type", ""), "summary") << s.dump();  // one summary last, the tunnel's counters in it
  const auto& a = s["adb"];
  EXPECT_EQ(a["serial"], "FAKE0001");
  EXPECT_TRUE(a["connected"].get<bool>());
  EXPECT_GT(a["channels"]["GCS"]["to_board"].get<uint64_t>(), 0u) << a.dump();
  EXPECT_GT(a["channels"]["GCS"]["from_board"].get<uint64_t>(), 0u) << a.dump();  // the PARAM_VALUE, HEARTBEAT
  EXPECT_EQ(a["channels"]["HIL"]["to_board"].get<uint64_t>(), 0u);                 // no simulator here
  const auto calls = fake.calls();
  EXPECT_EQ(calls.back(), "-s FAKE0001 forward --remove tcp:" + std::to_string(fake.relay_port()));
  EXPECT_TRUE(fake.stop_relays());
  board.signal(SIGINT);
  board.wait(10s);
}

TEST(BridgeAdbE2E, WithoutAdbItSaysWhichPackageToInstallAndAnAddressIsExclusive) {
  {
    test::NoAdbOnPath no_adb;
    auto r = test::run_hitl({"bridge", "--adb", "--duration", "1", "--clients", "0"}, 30s);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("hitl bridge: --adb: adb not found on PATH: install the Debian package adb"), std::string::npos) << r.err;
  }
  auto r = test::run_hitl({"bridge", "--adb", "-i", "192.168.101.2", "--duration", "1"}, 30s);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("excludes"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace hitl
