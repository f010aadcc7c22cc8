// Deterministic replay (docs/replay.md) through the real binary against hitl target --lockstep:
// two sessions flying the square give bit-identical HIL_SENSOR, HIL_GPS and ODOMETRY streams;
// hitl replay of the recording reproduces the board's actuator outputs exactly, and --compare
// reports the divergence when a parameter changed; bad recordings exit 2 naming the problem.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;

struct TargetPorts {
  uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), vio = test::free_udp_port();
};

std::unique_ptr<test::Process> start_target(const TargetPorts& p) {
  auto board = std::make_unique<test::Process>(std::vector<std::string>{test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(p.hil), "--gcs-port",
                       std::to_string(p.gcs), "--vio-port", std::to_string(p.vio), "--lockstep"});
  EXPECT_TRUE(board->wait_for_stderr("EMULATED", 10s)) << board->err();
  return board;
}

/// hitl sim --lockstep --speed 0 flying the square against a fresh hitl target, recorded to `tlog`.
void record_square(const std::string& tlog) {
  const TargetPorts p;
  auto board = start_target(p);
  test::Process sim({test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(p.hil), "--local-port",
                     std::to_string(test::free_udp_port()), "--vio-ip", "127.0.0.1", "--vio-port", std::to_string(p.vio),
                     "--clients", "0", "--lockstep", "--speed", "0", "-t", std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json",
                     "--record", tlog});
  EXPECT_EQ(sim.wait(120s), 0) << sim.err();
  board->signal(SIGINT);
  board->wait(20s);
  const auto j = nlohmann::json::parse(sim.out_lines().back());
  EXPECT_EQ(j["end"], "trajectory_done") << sim.err();
}

/// The payloads of each message the simulator sent, by name, in order.
std::map<std::string, std::vector<std::vector<uint8_t>>> sent_payloads(const std::string& tlog) {
  std::map<std::string, std::vector<std::vector<uint8_t>>> out;
  auto reader = mavlink::TlogReader::open(tlog);
  EXPECT_TRUE(reader) << tlog;
  if (!reader) return out;
  const auto set = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(set);
  mavlink::TlogRecord r;
  while (reader->next(r))
    parser.parse_datagram(r.frame, [&](const mavlink::Frame& f) {
      const char* name = f.is<msg::HilSensor>() ? "HIL_SENSOR" : f.is<msg::HilGps>() ? "HIL_GPS" : f.is<msg::Odometry>() && f.compid == 197 ? "ODOMETRY" : nullptr;
      if (name) out[name].emplace_back(f.payload.begin(), f.payload.begin() + f.payload_len);
    });
  return out;
}

class ReplayE2E : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(test::temp_dir());
    record_square(*dir_ + "/a.tlog");
    record_square(*dir_ + "/b.tlog");
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string* dir_;
};
std::string* ReplayE2E::dir_ = nullptr;

TEST_F(ReplayE2E, TheSameSeedAndAnswersGiveABitIdenticalSensorStream) {
  const auto a = sent_payloads(*dir_ + "/a.tlog"), b = sent_payloads(*dir_ + "/b.tlog");
  for (const char* name : {"HIL_SENSOR", "HIL_GPS", "ODOMETRY"}) {
    ASSERT_TRUE(a.count(name) && b.count(name)) << name;
    EXPECT_GT(a.at(name).size(), 1000u) << name;
    ASSERT_EQ(a.at(name).size(), b.at(name).size()) << name;
    for (std::size_t i = 0; i < a.at(name).size(); ++i)
      ASSERT_EQ(a.at(name)[i], b.at(name)[i]) << name << " #" << i << " differs";
  }
}

nlohmann::json replay(const TargetPorts& p, const std::string& tlog, int expect_exit, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{test::hitl_binary(), "--json", "replay", tlog, "-i", "127.0.0.1", "--hil-port", std::to_string(p.hil),
                                "--vio-port", std::to_string(p.vio), "--local-port", std::to_string(test::free_udp_port()),
                                "--lockstep", "--compare"};
  args.insert(args.end(), extra.begin(), extra.end());
  test::Process r(args);
  EXPECT_EQ(r.wait(120s), expect_exit) << r.err();
  const auto lines = r.out_lines();
  if (lines.empty()) return nlohmann::json::object();
  return nlohmann::json::parse(lines.back());
}

TEST_F(ReplayE2E, ReplayInLockstepReproducesTheActuatorOutputsExactly) {
  const TargetPorts p;
  auto board = start_target(p);
  const auto j = replay(p, *dir_ + "/a.tlog", 0, {"--record", *dir_ + "/replayed.tlog"});
  board->signal(SIGINT);
  board->wait(20s);
  EXPECT_EQ(j["type"], "summary");
  EXPECT_EQ(j["end"], "done");
  EXPECT_EQ(j["steps_sent"], j["steps"]);
  EXPECT_EQ(j["fallbacks"].get<int>(), 0);
  const auto& c = j["compare"];
  EXPECT_EQ(c["matched"], "echo");
  EXPECT_TRUE(c["identical"].get<bool>()) << c.dump();
  EXPECT_GT(c["steps_compared"].get<uint64_t>(), 10000u);
  EXPECT_EQ(c["missing"].get<uint64_t>(), 0u);
  for (const auto& m : c["motors"]) EXPECT_EQ(m["max"].get<double>(), 0.0);
  EXPECT_TRUE(c["first_divergence"].is_null());
  // --record: what went to the board, as the session sent it, and what came back.
  const auto sent = sent_payloads(*dir_ + "/a.tlog"), resent = sent_payloads(*dir_ + "/replayed.tlog");
  EXPECT_EQ(sent.at("HIL_SENSOR"), resent.at("HIL_SENSOR"));
  EXPECT_EQ(sent.at("ODOMETRY"), resent.at("ODOMETRY"));
}

TEST_F(ReplayE2E, CompareReportsTheDivergenceOfABoardWithAChangedParameter) {
  const TargetPorts p;
  auto board = start_target(p);
  const auto set = test::run_hitl({"params", "--connect", "udp:127.0.0.1:" + std::to_string(p.gcs), "--local-port",
                                   std::to_string(test::free_udp_port()), "set", "MC_ROLLRATE_P", "0.10"});
  ASSERT_EQ(set.exit_code, 0) << set.out << set.err;
  const auto j = replay(p, *dir_ + "/a.tlog", 1);
  board->signal(SIGINT);
  board->wait(20s);
  const auto& c = j["compare"];
  EXPECT_FALSE(c["identical"].get<bool>()) << c.dump();
  ASSERT_TRUE(c["first_divergence"].is_object()) << c.dump();
  // The board answers alike until the roll rate controller has something to do: after the take-off.
  EXPECT_GT(c["first_divergence"]["t_s"].get<double>(), 1.0);
  double largest = 0;
  for (const auto& m : c["motors"]) {
    EXPECT_GE(m["max"].get<double>(), m["rms"].get<double>());
    largest = std::max(largest, m["max"].get<double>());
  }
  EXPECT_GT(largest, 1e-3);
}

TEST_F(ReplayE2E, APortInUseIsTwoAndABoardThatCannotBeReachedIsOne) {
  const uint16_t busy = test::free_udp_port();
  test::Process holder({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(busy), "--gcs-port", "0",
                        "--vio-port", "0"});
  ASSERT_TRUE(holder.wait_for_stderr("EMULATED", 10s)) << holder.err();
  const auto in_use = test::run_hitl({"replay", *dir_ + "/a.tlog", "--bind", "127.0.0.1", "--local-port", std::to_string(busy)});
  EXPECT_EQ(in_use.exit_code, 2) << in_use.err;
  EXPECT_NE(in_use.err.find("in use"), std::string::npos) << in_use.err;
  holder.signal(SIGINT);
  holder.wait(20s);
  // 255.255.255.255: the kernel refuses the send at once.
  const auto refused = test::run_hitl({"replay", *dir_ + "/a.tlog", "-i", "255.255.255.255", "--local-port",
                                       std::to_string(test::free_udp_port())});
  EXPECT_EQ(refused.exit_code, 1) << refused.err;
  EXPECT_NE(refused.err.find("sending to the board"), std::string::npos) << refused.err;
}

TEST(ReplayFly, ASquareFlownByHitlFlyThroughTheClientPortReplaysExactly) {
  // hitl fly's commands reach the board through the session's client port, forwarded at the start
  // of the next step: the replay puts them in that step's datagram, before its HIL_SENSOR.
  const auto dir = test::temp_dir();
  const TargetPorts p;
  const uint16_t clients = test::free_udp_port();
  {
    auto board = start_target(p);
    test::Process sim({test::hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(p.hil), "--local-port",
                       std::to_string(test::free_udp_port()), "--vio-ip", "127.0.0.1", "--vio-port", std::to_string(p.vio),
                       "--clients", std::to_string(clients), "--lockstep", "--speed", "5", "--record", dir + "/fly.tlog"});
    ASSERT_TRUE(sim.wait_for_stderr("HIL_SENSOR/HIL_GPS to", 10s)) << sim.err();
    const auto fly = test::run_hitl({"fly", "--connect", "udp:127.0.0.1:" + std::to_string(clients), "trajectory",
                                     std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json"},
                                    120s);
    EXPECT_EQ(fly.exit_code, 0) << fly.out << fly.err;
    sim.signal(SIGINT);
    EXPECT_EQ(sim.wait(20s), 0) << sim.err();
    board->signal(SIGINT);
    board->wait(20s);
  }
  const TargetPorts q;
  auto board = start_target(q);
  const auto j = replay(q, dir + "/fly.tlog", 0);
  board->signal(SIGINT);
  board->wait(20s);
  EXPECT_TRUE(j["compare"]["identical"].get<bool>()) << j.dump();
  EXPECT_GT(j["compare"]["steps_compared"].get<uint64_t>(), 10000u);
}

TEST(ReplayBadInput, BadRecordingsExitTwoNamingTheProblem) {
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/notes.tlog") << "not a telemetry log at all\n";
  std::ofstream(dir + "/huge.tlog").close();
  std::filesystem::resize_file(dir + "/huge.tlog", 300ull << 20);  // sparse
  const std::pair<std::string, std::string> cases[] = {
      {dir + "/notes.tlog", "is not a .tlog"},
      {dir + "/huge.tlog", "is 300 MiB, more than the 256 MiB a replay reads"},
      {dir + "/missing.tlog", "No such file or directory"},
      {std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json", "is not a .tlog"},
  };
  for (const auto& [file, words] : cases) {
    const auto r = test::run_hitl({"replay", file, "--hil-port", std::to_string(test::free_udp_port())});
    EXPECT_EQ(r.exit_code, 2) << file << "\n" << r.err;
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace hitl
