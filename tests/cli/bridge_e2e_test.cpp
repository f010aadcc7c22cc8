// hitl bridge end to end against hitl target: commands through its client port, an --endpoint that
// gets the board's traffic, link health (TIMESYNC round trip, HEARTBEAT age, loss) as JSON, the
// board going away and coming back without restarting the bridge, and bad input.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstring>
#include <thread>

#include "base/mavlink/messages.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

std::vector<std::string> board_args(uint16_t hil, uint16_t gcs) {
  return {test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
          std::to_string(gcs), "--vio-port", "0"};
}

/// The newest health line of the bridge's JSON output that satisfies `pred`, polling up to `timeout`.
template <class Pred>
std::optional<nlohmann::json> health_line(test::Process& bridge, Pred pred, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    const auto lines = bridge.out_lines();
    for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
      auto j = nlohmann::json::parse(*it, nullptr, false);
      if (!j.is_discarded() && pred(j)) return j;
    }
    std::this_thread::sleep_for(200ms);
  }
  return std::nullopt;
}

TEST(BridgeE2E, RoutesCommandsAndEndpointsReportsHealthAndSurvivesTheBoardGoingAway) {
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port(),
                 clients = test::free_udp_port(), qgc = test::free_udp_port();
  auto board = std::make_unique<test::Process>(board_args(hil, gcs));
  ASSERT_TRUE(board->wait_for_stderr("EMULATED", 10s)) << board->err();
  test::MavlinkPeer ground_station(qgc, 0, 255, 190);  // a QGroundControl listening on its port
  test::Process bridge({test::hitl_binary(), "--json", "bridge", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port",
                        std::to_string(local), "--clients", std::to_string(clients), "--endpoint",
                        "udp:127.0.0.1:" + std::to_string(qgc), "--duration", "120"});
  ASSERT_TRUE(bridge.wait_for_stderr("clients on", 10s)) << bridge.err();

  // A command through the bridge's client port, answered by the board.
  auto shell = test::run_hitl({"--json", "shell", "--session-port", std::to_string(clients), "-c", "qshell dsp_hitl status"});
  EXPECT_EQ(shell.exit_code, 0) << shell.err;
  EXPECT_NE(shell.out.find("IMU Section"), std::string::npos) << shell.out;

  // The endpoint gets the board's traffic.
  bool heartbeat = false;
  for (const auto& f : ground_station.receive_for(3s)) heartbeat = heartbeat || (f.sysid == 1 && f.is<mavlink::msg::Heartbeat>());
  EXPECT_TRUE(heartbeat);

  // Health: up, a TIMESYNC round trip, a recent HEARTBEAT, per-source loss, the three links.
  auto h = health_line(bridge, [](const nlohmann::json& j) { return j["board"] == "up" && !j["rtt_ms"].is_null(); }, 10s);
  ASSERT_TRUE(h) << bridge.out();
  EXPECT_LT((*h)["heartbeat_age_s"].get<double>(), 2.0);
  EXPECT_GT((*h)["rtt_ms"].get<double>(), 0.0);
  EXPECT_TRUE((*h)["loss"].contains("1/1")) << h->dump();
  ASSERT_EQ((*h)["links"].size(), 3u);
  EXPECT_EQ((*h)["links"][0]["name"], "board");
  EXPECT_GT((*h)["links"][0]["packets_in"].get<uint64_t>(), 0u);
  EXPECT_GT((*h)["links"][2]["packets_out"].get<uint64_t>(), 0u);  // to the endpoint

  // The board goes away (PX4 killed): said; then it comes back on the same ports: said, and
  // commands work again through the same bridge.
  board->signal(SIGKILL);
  board->wait(5s);
  EXPECT_TRUE(bridge.wait_for_stderr("board gone", 10s)) << bridge.err();
  board = std::make_unique<test::Process>(board_args(hil, gcs));
  ASSERT_TRUE(board->wait_for_stderr("EMULATED", 10s)) << board->err();
  EXPECT_TRUE(bridge.wait_for_stderr("board back", 15s)) << bridge.err();
  auto again = test::run_hitl({"shell", "--session-port", std::to_string(clients), "-c", "qshell dsp_hitl status"});
  EXPECT_EQ(again.exit_code, 0) << again.err;

  bridge.signal(SIGINT);
  EXPECT_EQ(bridge.wait(10s), 0);
  board->signal(SIGINT);
  board->wait(10s);
}

TEST(BridgeE2E, ForwardsNothingFromAnAddressThatIsNotTheBoard) {
  // Issue 19: 39 of 40 spoofed STATUSTEXT with the board's sysid from a foreign port reached a
  // client as the board's; a garbage flood counted as board input and grew the loss table.
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), local = test::free_udp_port(),
                 clients = test::free_udp_port();
  auto board = std::make_unique<test::Process>(board_args(hil, gcs));
  ASSERT_TRUE(board->wait_for_stderr("EMULATED", 10s)) << board->err();
  const uint16_t qgc = test::free_udp_port();
  test::MavlinkPeer ground_station(qgc, 0, 255, 190);
  test::Process bridge({test::hitl_binary(), "--json", "bridge", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port",
                        std::to_string(local), "--clients", std::to_string(clients), "--endpoint",
                        "udp:127.0.0.1:" + std::to_string(qgc), "--duration", "60"});
  ASSERT_TRUE(bridge.wait_for_stderr("clients on", 10s)) << bridge.err();
  test::MavlinkPeer client(0, clients, 255, 190);
  client.send(mavlink::msg::Heartbeat{});  // now a client of the bridge
  ASSERT_TRUE(health_line(bridge, [](const nlohmann::json& j) { return j["board"] == "up" && !j["rtt_ms"].is_null(); }, 10s));

  test::MavlinkPeer intruder(0, local, 1, 1);  // the board's sysid/compid, another port
  mavlink::msg::Statustext spoof{};
  const std::string words = "SPOOFED";
  std::copy(words.begin(), words.end(), spoof.text.begin());
  for (int i = 0; i < 40; ++i) intruder.send(spoof);
  std::vector<uint8_t> junk(200);
  uint32_t x = 7;
  for (int i = 0; i < 3000; ++i) {
    for (auto& b : junk) b = static_cast<uint8_t>((x = x * 1664525u + 1013904223u) >> 24);
    junk[0] = 0xFE;  // MAVLink 1 start: unknown ids pass unchecked, each with another sysid/compid
    intruder.send_bytes(junk);
    if (i % 500 == 0) std::this_thread::sleep_for(5ms);
  }
  // The udp: endpoint's socket hears its peer only: the bridge's port towards "QGroundControl",
  // written to by a stranger.
  std::optional<net::SocketAddress> endpoint_port;
  for (int i = 0; i < 50 && !endpoint_port; ++i)
    if (ground_station.endpoint().wait_readable(100))
      if (auto d = ground_station.endpoint().receive()) endpoint_port = d->from;
  ASSERT_TRUE(endpoint_port);
  test::MavlinkPeer stranger(0, endpoint_port->port(), 255, 190);
  for (int i = 0; i < 10; ++i) stranger.send(mavlink::msg::Heartbeat{});
  bool spoofed = false;
  for (const auto& f : client.receive_for(2s)) {
    if (f.is<mavlink::msg::Statustext>()) {
      const auto t = f.as<mavlink::msg::Statustext>();
      spoofed = spoofed || std::string(t.text.data(), strnlen(t.text.data(), t.text.size())) == words;
    }
  }
  EXPECT_FALSE(spoofed);
  // Each datagram of the intruder's was read and ignored, or dropped by the kernel (the board
  // socket's buffer holds --queue-ms of the board's stream, not seconds of a flood), and counted.
  auto h = health_line(
      bridge, [](const nlohmann::json& j) { return j["ignored_other_address"].get<uint64_t>() + j["kernel_rx_drops"].get<uint64_t>() >= 3050; },
      10s);
  ASSERT_TRUE(h) << bridge.out_lines().back();
  EXPECT_LE((*h)["loss"].size(), 2u) << h->dump();  // the board's own sources only
  // The round trip is back to what it was once the flood is over.
  EXPECT_TRUE(health_line(
      bridge, [](const nlohmann::json& j) { return !j["rtt_ms"].is_null() && j["rtt_ms"].get<double>() < 50.0 && j["uptime_s"].get<double>() > 0; },
      10s));
  bridge.signal(SIGINT);
  EXPECT_EQ(bridge.wait(10s), 0);
  board->signal(SIGINT);
  board->wait(10s);
}

TEST(BridgeE2E, BadInputIsRefusedWithTheReason) {
  auto bad = test::run_hitl({"bridge", "--endpoint", "serial:/dev/ttyUSB0", "--duration", "1"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("serial:/dev/ttyUSB0"), std::string::npos) << bad.err;
  // The client port taken (by a running session or bridge): refused, saying what is likely running.
  test::MavlinkPeer squatter(0, 0);
  const uint16_t taken = squatter.endpoint().local_address().port();
  auto busy = test::run_hitl({"bridge", "--clients", std::to_string(taken), "--local-port", std::to_string(test::free_udp_port()),
                              "--duration", "1"});
  EXPECT_EQ(busy.exit_code, 2);  // a port in use: 2, as in every command (issue 18)
  EXPECT_NE(busy.err.find("hitl sim or another hitl bridge"), std::string::npos) << busy.err;
}

}  // namespace
}  // namespace hitl
