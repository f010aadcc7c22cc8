// AdbTunnel (engine/net/adb_tunnel.h) against the stand-in adb, which starts the real
// hitl-adb-relay on this machine: what hitl asks adb to do, in order, and what it says when adb,
// the board or the relay is missing. And the hitl-adb-relay program itself.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>

#include <fstream>
#include <mutex>
#include <thread>

#include "engine/net/adb_tunnel.h"
#include "engine/net/udp_endpoint.h"
#include "tests/support/fake_adb.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
using adb::Channel;

net::UdpEndpoint open_udp() {
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  c.policy = net::PartnerPolicy::LastSender;
  return std::move(net::UdpEndpoint::open(c).value());
}

std::string receive_text(net::UdpEndpoint& ep, std::chrono::milliseconds timeout = 5s) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (auto d = ep.receive()) return std::string(d->bytes.begin(), d->bytes.end());
    ep.wait_readable(20);
  }
  return {};
}

/// The board's ports on this machine, and the relay options that point the relay at them.
struct Board {
  net::UdpEndpoint hil = open_udp(), vio = open_udp(), gcs = open_udp();
  std::string relay_args() const {
    return "--hil-port " + std::to_string(hil.local_address().port()) + " --vio-port " + std::to_string(vio.local_address().port()) +
           " --gcs-port " + std::to_string(gcs.local_address().port()) + " --hil-source-port 0 --gcs-source-port 0";
  }
};

struct Events {
  std::mutex mutex;
  std::string text;
  void add(const std::string& l) {
    std::lock_guard<std::mutex> lock(mutex);
    text += l + "\n";
  }
  std::string all() {
    std::lock_guard<std::mutex> lock(mutex);
    return text;
  }
};

net::AdbTunnelConfig config_for(Events& events, std::vector<std::string> relay_binaries = {HITL_ADB_RELAY_BINARY}) {
  net::AdbTunnelConfig c;
  c.relay_binaries = std::move(relay_binaries);
  c.tunnel.on_event = [&events](const std::string& l) { events.add(l); };
  return c;
}

TEST(AdbTunnel, PushesStartsCarriesAndRemovesTheForward) {
  Board board;
  test::FakeAdb fake({.relay_args = board.relay_args()});
  Events events;
  uint16_t forward_port = 0;
  {
    auto tunnel = net::AdbTunnel::open(config_for(events));
    ASSERT_TRUE(tunnel) << tunnel.error().message << "\n" << events.all();
    forward_port = (*tunnel)->forward_port();
    EXPECT_EQ(forward_port, fake.relay_port());
    EXPECT_EQ((*tunnel)->serial(), "FAKE0001");
    EXPECT_TRUE(fake.pushed_relay_exists());
    const std::string said = events.all();
    EXPECT_NE(said.find("hitl-adb-relay is not on the board; pushing " + std::string(HITL_ADB_RELAY_BINARY) + " to /tmp/hitl-adb-relay"),
              std::string::npos) << said;
    EXPECT_NE(said.find("started /tmp/hitl-adb-relay on the board: hitl-adb-relay: listening on TCP"), std::string::npos) << said;
    // What hitl asked adb to do, in order.
    int at = fake.find_call("devices");
    EXPECT_EQ(at, 0);
    at = fake.find_call("-s FAKE0001 forward tcp:0 tcp:14590", at);
    EXPECT_GT(at, 0);
    at = fake.find_call("-s FAKE0001 shell hitl-adb-relay --daemon --port 14590", at);  // the board package's?
    EXPECT_GT(at, 0);
    at = fake.find_call("-s FAKE0001 shell /tmp/hitl-adb-relay --daemon --port 14590", at);  // pushed earlier?
    EXPECT_GT(at, 0);
    at = fake.find_call("-s FAKE0001 shell uname -m", at);
    EXPECT_GT(at, 0);
    at = fake.find_call("-s FAKE0001 push " + std::string(HITL_ADB_RELAY_BINARY) + " /tmp/hitl-adb-relay", at);
    EXPECT_GT(at, 0);
    at = fake.find_call("-s FAKE0001 shell chmod 755 /tmp/hitl-adb-relay", at);
    EXPECT_GT(at, 0);
    at = fake.find_call("-s FAKE0001 shell /tmp/hitl-adb-relay --daemon --port 14590", at);
    EXPECT_GT(at, 0);

    // Datagrams through it, both ways.
    net::UdpEndpoint sim = open_udp();
    ASSERT_TRUE(sim.send_to((*tunnel)->local_endpoint(Channel::Hil), std::vector<uint8_t>{'h', 'i', 'l'}).ok());
    EXPECT_EQ(receive_text(board.hil), "hil");
    ASSERT_TRUE(board.hil.send(std::vector<uint8_t>{'a', 'c', 't'}).ok());
    EXPECT_EQ(receive_text(sim), "act");
    ASSERT_TRUE(sim.send_to((*tunnel)->local_endpoint(Channel::Vio), std::vector<uint8_t>{'o', 'd', 'o'}).ok());
    EXPECT_EQ(receive_text(board.vio), "odo");
    EXPECT_NE((*tunnel)->describe().find("board FAKE0001 through adb forward tcp:" + std::to_string(forward_port) + " -> tcp:14590"),
              std::string::npos) << (*tunnel)->describe();
  }
  // Gone: the forward is removed; the relay stays on the board for the next time.
  const auto calls = fake.calls();
  ASSERT_FALSE(calls.empty());
  EXPECT_EQ(calls.back(), "-s FAKE0001 forward --remove tcp:" + std::to_string(forward_port));

  // The next time the relay answers at once: no start, no push.
  const auto before = static_cast<int>(fake.calls().size());
  Events again;
  auto second = net::AdbTunnel::open(config_for(again));
  ASSERT_TRUE(second) << second.error().message;
  EXPECT_EQ(fake.find_call("-s FAKE0001 shell", before), -1);
  EXPECT_EQ(fake.find_call("-s FAKE0001 push", before), -1);
  EXPECT_GT(fake.find_call("-s FAKE0001 forward tcp:0 tcp:14590", before), 0);
  second->reset();
  EXPECT_TRUE(fake.stop_relays());
  EXPECT_NE(fake.relay_log().find("hitl-adb-relay: stopped"), std::string::npos) << fake.relay_log();
}

TEST(AdbTunnel, ARelayThatDiesIsStartedAgainAndTheLinkComesBack) {
  Board board;
  test::FakeAdb fake({.relay_args = board.relay_args()});
  fake.install_relay_on_device(HITL_ADB_RELAY_BINARY);
  Events events;
  auto tunnel = net::AdbTunnel::open(config_for(events));
  ASSERT_TRUE(tunnel) << tunnel.error().message;
  const auto hil = (*tunnel)->local_endpoint(Channel::Hil);
  const int before = static_cast<int>(fake.calls().size());
  ASSERT_TRUE(fake.stop_relays());  // the relay is killed on the board
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (std::chrono::steady_clock::now() < deadline && (*tunnel)->stats().connects < 2) std::this_thread::sleep_for(20ms);
  const auto s = (*tunnel)->stats();
  EXPECT_EQ(s.connects, 2u) << events.all();
  EXPECT_EQ(s.link_losses, 1u);
  EXPECT_TRUE(s.connected);
  // Lost, then: the same forward (refused), a new forward, the relay started again.
  int at = fake.find_call("-s FAKE0001 forward --remove tcp:", before);
  EXPECT_GE(at, before);
  at = fake.find_call("-s FAKE0001 forward tcp:0 tcp:14590", at);
  EXPECT_GT(at, before);
  at = fake.find_call("-s FAKE0001 shell hitl-adb-relay --daemon --port 14590", at);
  EXPECT_GT(at, before);
  EXPECT_NE(events.all().find("adb tunnel: link to the relay lost"), std::string::npos) << events.all();
  EXPECT_NE(events.all().find("adb tunnel: link to the relay restored"), std::string::npos) << events.all();
  // The local endpoint is the same; traffic flows again.
  EXPECT_EQ((*tunnel)->local_endpoint(Channel::Hil), hil);
  net::UdpEndpoint sim = open_udp();
  ASSERT_TRUE(sim.send_to(hil, std::vector<uint8_t>{'b', 'a', 'c', 'k'}).ok());
  EXPECT_EQ(receive_text(board.hil), "back");
}

TEST(AdbTunnel, TheBoardPackagesRelayIsStartedWithoutAPush) {
  Board board;
  test::FakeAdb fake({.relay_args = board.relay_args()});
  fake.install_relay_on_device(HITL_ADB_RELAY_BINARY);
  Events events;
  auto tunnel = net::AdbTunnel::open(config_for(events));
  ASSERT_TRUE(tunnel) << tunnel.error().message;
  EXPECT_NE(events.all().find("started hitl-adb-relay on the board"), std::string::npos) << events.all();
  EXPECT_EQ(fake.find_call("-s FAKE0001 push"), -1);
  EXPECT_FALSE(fake.pushed_relay_exists());
}

TEST(AdbTunnel, NoRelayForTheBoardsArchitectureSaysWhatToDo) {
  test::FakeAdb fake({});
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/hitl-adb-relay") << "#!/bin/sh\n";
  Events events;
  auto tunnel = net::AdbTunnel::open(config_for(events, {dir + "/missing", dir + "/hitl-adb-relay"}));
  ASSERT_FALSE(tunnel);
  const std::string& m = tunnel.error().message;
  EXPECT_NE(m.find("hitl-adb-relay is not on the board and there is no copy built for the board's"), std::string::npos) << m;
  EXPECT_NE(m.find(dir + "/missing (missing)"), std::string::npos) << m;
  EXPECT_NE(m.find(dir + "/hitl-adb-relay (not an executable)"), std::string::npos) << m;
  EXPECT_NE(m.find("install the voxl-hitl-px4-scripts package on the board"), std::string::npos) << m;
  EXPECT_EQ(fake.find_call("-s FAKE0001 push"), -1);
  // The forward made on the way is removed.
  EXPECT_GE(fake.find_call("-s FAKE0001 forward --remove tcp:"), 0);
}

TEST(AdbTunnel, AdbMissingNamesThePackage) {
  test::NoAdbOnPath no_adb;
  Events events;
  auto tunnel = net::AdbTunnel::open(config_for(events));
  ASSERT_FALSE(tunnel);
  EXPECT_NE(tunnel.error().message.find("adb not found on PATH: install the Debian package adb"), std::string::npos)
      << tunnel.error().message;
}

TEST(AdbTunnel, NoBoardSaysToPlugItIn) {
  test::FakeAdb fake({.devices = ""});
  Events events;
  auto tunnel = net::AdbTunnel::open(config_for(events));
  ASSERT_FALSE(tunnel);
  EXPECT_NE(tunnel.error().message.find("no board attached to adb: plug in the VOXL2's USB-C cable"), std::string::npos)
      << tunnel.error().message;
  EXPECT_EQ(fake.calls(), std::vector<std::string>{"devices"});
}

TEST(AdbTunnel, TwoDevicesNeedASerialAndTheSerialIsUsedThroughout) {
  Board board;
  test::FakeAdb fake({.devices = "PHONE1 device;VOXL2B device", .relay_args = board.relay_args()});
  Events events;
  auto ambiguous = net::AdbTunnel::open(config_for(events));
  ASSERT_FALSE(ambiguous);
  EXPECT_NE(ambiguous.error().message.find("2 devices are attached to adb (PHONE1, VOXL2B): choose the board with --adb-serial"),
            std::string::npos) << ambiguous.error().message;
  auto config = config_for(events);
  config.serial = "VOXL2B";
  auto tunnel = net::AdbTunnel::open(config);
  ASSERT_TRUE(tunnel) << tunnel.error().message;
  for (const auto& call : fake.calls())
    if (call != "devices") {
      EXPECT_EQ(call.rfind("-s VOXL2B ", 0), 0u) << call;
    }
  auto unknown = config;
  unknown.serial = "NOPE";
  auto missing = net::AdbTunnel::open(unknown);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("--adb-serial NOPE: no such device attached"), std::string::npos) << missing.error().message;
}

TEST(AdbRelayProgram, HelpUsagePortInUseAndSigterm) {
  const std::string relay = HITL_ADB_RELAY_BINARY;
  {
    test::Process help({relay, "--help"});
    EXPECT_EQ(help.wait(10s), 0);
    EXPECT_NE(help.out().find("Usage: hitl-adb-relay [options]"), std::string::npos);
    EXPECT_NE(help.out().find("--port N"), std::string::npos);
  }
  {
    test::Process bad({relay, "--port", "seventy"});
    EXPECT_EQ(bad.wait(10s), 2);
    EXPECT_NE(bad.err().find("--port: 'seventy' is not a port number"), std::string::npos) << bad.err();
    test::Process bad_bind({relay, "--bind", "board.local"});
    EXPECT_EQ(bad_bind.wait(10s), 2);
    EXPECT_NE(bad_bind.err().find("--bind: 'board.local' is not an IPv4 address"), std::string::npos) << bad_bind.err();
  }
  const uint16_t port = test::free_udp_port();
  const std::vector<std::string> args{relay, "--port", std::to_string(port), "--hil-source-port", "0", "--gcs-source-port", "0"};
  test::Process first(args);
  ASSERT_TRUE(first.wait_for_stderr("listening on TCP 127.0.0.1:" + std::to_string(port), 10s)) << first.err();
  {
    test::Process second(args);
    EXPECT_EQ(second.wait(10s), 1);
    EXPECT_NE(second.err().find("cannot listen on TCP 127.0.0.1:" + std::to_string(port) +
                                ": Address already in use (is another hitl-adb-relay running?"),
              std::string::npos) << second.err();
  }
  {
    auto daemon_args = args;
    daemon_args.push_back("--daemon");
    daemon_args.push_back("--log");
    daemon_args.push_back(test::temp_dir() + "/relay.log");
    test::Process second(daemon_args);
    EXPECT_EQ(second.wait(10s), 1);
    EXPECT_NE(second.err().find("Address already in use"), std::string::npos) << second.err();
  }
  first.signal(SIGTERM);
  EXPECT_EQ(first.wait(10s), 0);
  EXPECT_NE(first.err().find("hitl-adb-relay: stopped"), std::string::npos) << first.err();
}

}  // namespace
}  // namespace hitl
