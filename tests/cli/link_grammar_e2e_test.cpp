// The one link grammar (engine/net/link_spec.h) through the real binary: hitl bridge serving ground
// station tools on tcpin: (a hitl command and a raw TCP client at once), a command waiting on
// --connect tcpin: for the bridge to connect to it, --px4-sitl in the grammar and in the spellings
// before it, the config file, and every malformed link refused with exit 2 naming the option.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>
#include <thread>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/net/open_link.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

std::unique_ptr<test::Process> start_board(uint16_t hil, uint16_t gcs) {
  auto board = std::make_unique<test::Process>(std::vector<std::string>{
      test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port", std::to_string(gcs),
      "--vio-port", "0"});
  EXPECT_TRUE(board->wait_for_stderr("EMULATED", 10s)) << board->err();
  return board;
}

/// Whether a HEARTBEAT from the board (sysid 1) arrives on `link` within `timeout_s`.
bool board_heartbeat_on(net::Link& link, double timeout_s) {
  static const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  bool seen = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
  while (!seen && std::chrono::steady_clock::now() < end) {
    if (!link.wait_readable(100)) continue;
    link.drain(parser, [&](const mavlink::Frame& f) { seen = seen || (f.sysid == 1 && f.is<mavlink::msg::Heartbeat>()); });
  }
  return seen;
}

TEST(LinkGrammarE2E, BridgeServesGroundStationToolsOnTcpin) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port(),
                 tcp = test::free_udp_port();  // a free number; TCP on it is very likely free too
  auto board = start_board(hil, gcs);
  test::Process bridge({test::hitl_binary(), "--json", "bridge", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port",
                        std::to_string(local), "--clients", "0", "--endpoint", "tcpin:127.0.0.1:" + std::to_string(tcp),
                        "--duration", "60"});
  ASSERT_TRUE(bridge.wait_for_stderr("tcpin:127.0.0.1:" + std::to_string(tcp), 10s)) << bridge.err();

  // A ground station tool connects in and gets the board's traffic ...
  net::LinkSettings settings;
  settings.name = "test GCS";
  settings.connect_timeout_ms = 2000;
  auto gcs_tool = net::open_link(net::parse_link_spec("tcp:127.0.0.1:" + std::to_string(tcp)).value(), settings);
  ASSERT_TRUE(gcs_tool.ok()) << gcs_tool.error().message;
  EXPECT_TRUE(board_heartbeat_on(*gcs_tool.value(), 5.0));
  // ... while a hitl command connects too, and its command is answered by the board.
  auto shell = test::run_hitl({"--json", "shell", "--connect", "tcp:127.0.0.1:" + std::to_string(tcp), "-c", "qshell dsp_hitl status"});
  EXPECT_EQ(shell.exit_code, 0) << shell.err;
  EXPECT_NE(shell.out.find("IMU Section"), std::string::npos) << shell.out;
  EXPECT_TRUE(board_heartbeat_on(*gcs_tool.value(), 3.0));  // the first tool is still served
  EXPECT_TRUE(bridge.wait_for_stderr("connected (", 5s)) << bridge.err();

  // The health lines (one a second) name the tcpin link; it carried frames both ways.
  const std::string name = "tcpin:127.0.0.1:" + std::to_string(tcp);
  const auto both_ways = [&](const nlohmann::json& j) {
    for (const auto& l : j["links"])
      if (l["name"] == name && l["packets_in"].get<uint64_t>() > 0 && l["packets_out"].get<uint64_t>() > 0) return true;
    return false;
  };
  bool carried = false;
  for (int i = 0; i < 50 && !carried; ++i) {
    for (const auto& line : bridge.out_lines()) {
      auto j = nlohmann::json::parse(line, nullptr, false);
      carried = carried || (!j.is_discarded() && j.contains("links") && both_ways(j));
    }
    if (!carried) std::this_thread::sleep_for(100ms);
  }
  EXPECT_TRUE(carried) << bridge.out();
  bridge.signal(SIGINT);
  EXPECT_EQ(bridge.wait(10s), 0);
  board->signal(SIGINT);
  board->wait(10s);
}

TEST(LinkGrammarE2E, ACommandWaitsOnTcpinForTheBridgeToConnect) {
  // --connect tcpin:PORT: the command listens; the bridge's tcp: endpoint connects to it (retrying
  // every 2 s), and the command talks to the board through it.
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port(),
                 tcp = test::free_udp_port();
  auto board = start_board(hil, gcs);
  test::Process bridge({test::hitl_binary(), "bridge", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port",
                        std::to_string(local), "--clients", "0", "--endpoint", "tcp:127.0.0.1:" + std::to_string(tcp),
                        "--duration", "60"});
  ASSERT_TRUE(bridge.wait_for_stderr("tcp:127.0.0.1:" + std::to_string(tcp), 10s)) << bridge.err();
  auto shell = test::run_hitl({"--json", "shell", "--connect", "tcpin:127.0.0.1:" + std::to_string(tcp), "--timeout", "10", "-c",
                               "qshell dsp_hitl status"});
  EXPECT_EQ(shell.exit_code, 0) << shell.err;
  EXPECT_NE(shell.out.find("IMU Section"), std::string::npos) << shell.out;
  bridge.signal(SIGINT);
  bridge.wait(10s);
  board->signal(SIGINT);
  board->wait(10s);
}

TEST(LinkGrammarE2E, OldAndNewSpellingsOfTheConnectOption) {
  // One local port for every command: the board's instance answers only the first port it heard.
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port();
  auto board = start_board(hil, gcs);
  for (const std::string& connect : {"udp:127.0.0.1:" + std::to_string(gcs), "udp:localhost:" + std::to_string(gcs)}) {
    auto shell = test::run_hitl({"--json", "shell", "--connect", connect, "--local-port", std::to_string(local), "-c",
                                 "qshell dsp_hitl status"});
    EXPECT_EQ(shell.exit_code, 0) << connect << ": " << shell.err;
  }
  // inspect: the grammar's udp:HOST:PORT, and HOST:PORT as before.
  for (const std::string& connect : {"udp:127.0.0.1:" + std::to_string(gcs), "127.0.0.1:" + std::to_string(gcs)}) {
    auto inspect = test::run_hitl({"--json", "inspect", "--connect", connect, "--local-port", std::to_string(local), "--duration", "2"});
    EXPECT_EQ(inspect.exit_code, 0) << connect << ": " << inspect.err;
    EXPECT_NE(inspect.out.find("HEARTBEAT"), std::string::npos) << connect << ": " << inspect.out;
  }
  board->signal(SIGINT);
  board->wait(10s);
}

TEST(LinkGrammarE2E, Px4SitlTakesTheGrammarAndTheSpellingsBeforeIt) {
  const uint16_t port = test::free_udp_port();
  for (const std::string& spelled : {"tcpin:127.0.0.1:" + std::to_string(port), "tcp:" + std::to_string(port)}) {
    test::Process sim({test::hitl_binary(), "sim", "--px4-sitl", spelled, "--no-vio", "--clients", "0", "--bind", "127.0.0.1"});
    EXPECT_TRUE(sim.wait_for_stderr("waiting for PX4 SITL to connect to TCP 127.0.0.1:" + std::to_string(port), 10s))
        << spelled << ": " << sim.err();
    sim.signal(SIGINT);
    sim.wait(10s);
  }
  // UDP: PX4's simulator port, at an address (udp:HOST:PORT) or at -i (udp:PORT).
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--px4-sitl", "udp:127.0.0.1:" + std::to_string(port)}, {"-i", "127.0.0.1", "--px4-sitl", "udp:" + std::to_string(port)}}) {
    std::vector<std::string> argv{test::hitl_binary(), "sim", "--no-vio", "--clients", "0", "--bind", "127.0.0.1",
                                  "--local-port", std::to_string(test::free_udp_port()), "--duration", "0.5"};
    argv.insert(argv.end(), args.begin(), args.end());
    test::Process sim(argv);
    EXPECT_TRUE(sim.wait_for_stderr("HIL_SENSOR/HIL_GPS to 127.0.0.1:" + std::to_string(port), 10s)) << sim.err();
    EXPECT_TRUE(sim.wait_for_stderr("(lockstep)", 1s)) << sim.err();  // PX4 SITL: always lockstep
    sim.wait(20s);
  }
}

TEST(LinkGrammarE2E, SimsGroundStationTakesTheGrammarsUdpAndHostPort) {
  for (const bool spelled : {true, false}) {
    const uint16_t qgc = test::free_udp_port();
    test::MavlinkPeer ground_station(qgc, 0, 255, 190);  // a QGroundControl listening on its port
    const std::string gcs = (spelled ? "udp:127.0.0.1:" : "127.0.0.1:") + std::to_string(qgc);
    test::Process sim({test::hitl_binary(), "sim", "--gcs", gcs, "--no-vio", "--clients", std::to_string(test::free_udp_port()),
                       "--bind", "127.0.0.1", "--local-port", std::to_string(test::free_udp_port()), "--hil-port",
                       std::to_string(test::free_udp_port()), "--duration", "3"});
    bool simulator = false;  // the session's own HEARTBEAT (sysid 250) reaches the ground station
    for (const auto& f : ground_station.receive_for(3s)) simulator = simulator || f.sysid == 250;
    EXPECT_TRUE(simulator) << gcs << ": " << sim.err();
    sim.wait(20s);
  }
}

TEST(LinkGrammarE2E, TheConfigFileTakesTheGrammar) {
  const std::string dir = test::temp_dir();
  const uint16_t tcp = test::free_udp_port();
  std::ofstream(dir + "/bridge.toml") << "[bridge]\nendpoint = [\"tcpin:127.0.0.1:" << tcp << "\"]\nclients = 0\nduration = 1\n";
  auto r = test::run_hitl({"--config", dir + "/bridge.toml", "bridge", "--local-port", std::to_string(test::free_udp_port())});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("tcpin:127.0.0.1:" + std::to_string(tcp)), std::string::npos) << r.err;
  std::ofstream(dir + "/bad.toml") << "[bridge]\nendpoint = [\"tcpin:seventy\"]\n";
  auto bad = test::run_hitl({"--config", dir + "/bad.toml", "bridge"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--endpoint 'tcpin:seventy'"), std::string::npos) << bad.err;
}

TEST(LinkGrammarE2E, AMalformedLinkExits2NamingTheOptionAndTheProblem) {
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases{
      {{"bridge", "--endpoint", "tcpin:x", "--duration", "1"}, "--endpoint 'tcpin:x': 'x' is not a port number"},
      {{"bridge", "--endpoint", "tcp:5760", "--duration", "1"}, "--endpoint 'tcp:5760': expected tcp:HOST:PORT"},
      {{"bridge", "--endpoint", "serial:/dev/ttyUSB0", "--duration", "1"}, "unknown kind 'serial'"},
      {{"shell", "--connect", "tcp:5760", "-c", "ver all"}, "--connect: 'tcp:5760': expected tcp:HOST:PORT"},
      {{"arm", "--connect", "bogus"}, "--connect: 'bogus': expected udp:HOST:PORT, udpin:[HOST:]PORT, tcp:HOST:PORT or tcpin:[HOST:]PORT"},
      {{"inspect", "--connect", "tcp:127.0.0.1:5760", "--duration", "1"}, "--connect 'tcp:127.0.0.1:5760': inspect times UDP"},
      {{"inspect", "--connect", "udp:127.0.0.1", "--duration", "1"}, "--connect 'udp:127.0.0.1': expected udp:HOST:PORT"},
      {{"sim", "--gcs", "tcp:127.0.0.1:5760", "--local-port", "0", "--duration", "1"}, "--gcs 'tcp:127.0.0.1:5760': the ground station is a UDP peer"},
      {{"sim", "--gcs", "localhost", "--local-port", "0", "--duration", "1"}, "--gcs 'localhost': expected udp:HOST:PORT or HOST:PORT"},
      {{"sim", "--px4-sitl", "tcp:127.0.0.1:4560", "--duration", "1"}, "--px4-sitl 'tcp:127.0.0.1:4560': PX4 SITL connects to the simulator"},
      {{"sim", "--px4-sitl", "udpin:14560", "--duration", "1"}, "--px4-sitl 'udpin:14560'"},
      {{"sim", "--px4-sitl", "ftp:1", "--duration", "1"}, "--px4-sitl 'ftp:1': unknown kind 'ftp'"},
      {{"sim", "--px4-sitl", "tcpin:99999", "--duration", "1"}, "--px4-sitl 'tcpin:99999': '99999' is not a port number"},
  };
  for (const auto& c : cases) {
    auto r = test::run_hitl(c.args, 30s);
    EXPECT_EQ(r.exit_code, 2) << c.args[0] << " " << c.args[2] << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

TEST(LinkGrammarE2E, AnEndpointThatCannotBeOpenedExits2NamingIt) {
  // A well-formed --endpoint whose port another socket holds: unavailable, 2, the endpoint named.
  net::LinkSettings settings;
  settings.name = "holder";
  net::LinkSpec held_spec;
  held_spec.kind = net::LinkSpec::Kind::UdpIn;
  held_spec.host = "127.0.0.1";
  auto held = net::open_link(held_spec, settings);
  ASSERT_TRUE(held.ok()) << held.error().message;
  const std::string endpoint = "udpin:127.0.0.1:" + std::to_string((*held)->local_address()->port());
  auto r = test::run_hitl({"bridge", "--endpoint", endpoint, "--local-port", std::to_string(test::free_udp_port()), "--clients", "0",
                           "--duration", "1"},
                          30s);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--endpoint " + endpoint + ": cannot bind UDP"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace hitl
