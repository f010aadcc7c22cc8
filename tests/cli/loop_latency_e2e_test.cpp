// Loop latency at the board (docs/sim.md "Loop latency") through the real binary: hitl sim against
// hitl target, the summary's loop_latency. No speed is asserted: in lockstep every HIL_SENSOR but
// the last is answered by its echo (exact counts); a held HIL link (hil-delay) is a lower bound.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

nlohmann::json sim_against_target(bool lockstep, const std::vector<std::string>& extra) {
  const uint16_t hil = test::free_udp_port(), sim_local = test::free_udp_port();
  std::vector<std::string> target{test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                                  "--gcs-port", "0", "--vio-port", "0"};
  if (lockstep) target.push_back("--lockstep");
  test::Process board(target);
  EXPECT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  std::vector<std::string> args{test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil),
                                "--local-port", std::to_string(sim_local), "--no-vio", "--clients", "0"};
  if (lockstep) args.push_back("--lockstep");
  if (lockstep && std::find(extra.begin(), extra.end(), "--speed") == extra.end()) args.insert(args.end(), {"--speed", "0"});
  args.insert(args.end(), extra.begin(), extra.end());
  test::Process sim(args);
  EXPECT_EQ(sim.wait(120s), 0) << sim.err();
  board.signal(SIGINT);
  board.wait(20s);
  const auto lines = sim.out_lines();
  if (lines.empty()) return nlohmann::json::object();
  return nlohmann::json::parse(lines.back());
}

void expect_a_sane_distribution(const nlohmann::json& l) {
  const auto n = l["count"].get<uint64_t>();
  ASSERT_GT(n, 0u) << l.dump();
  EXPECT_GT(l["min_us"].get<double>(), 0.0);
  EXPECT_LE(l["min_us"].get<double>(), l["p50_us"].get<double>());
  EXPECT_LE(l["p50_us"].get<double>(), l["p95_us"].get<double>());
  EXPECT_LE(l["p95_us"].get<double>(), l["p99_us"].get<double>());
  EXPECT_LE(l["p99_us"].get<double>(), l["max_us"].get<double>());
  EXPECT_LT(l["max_us"].get<double>(), 10e6) << "an answer more than 10 s late on loopback";
  uint64_t binned = 0;
  ASSERT_EQ(l["histogram"].size(), 12u);
  for (const auto& b : l["histogram"]) binned += b["count"].get<uint64_t>();
  EXPECT_EQ(binned, n);
  EXPECT_TRUE(l["histogram"].back()["hi_us"].is_null());
}

TEST(LoopLatencyE2E, LockstepAgainstHitlTargetAnswersEverySensorByItsEcho) {
  const auto j = sim_against_target(true, {"--duration", "4"});
  ASSERT_TRUE(j.contains("loop_latency")) << j.dump();
  const auto& l = j["loop_latency"];
  EXPECT_EQ(l["matched"], "echo");
  // 4 s at 250 Hz: 1000 HIL_SENSORs; each answered by its echo but the last (the session ended).
  EXPECT_EQ(l["sensors"].get<uint64_t>(), 1000u);
  EXPECT_EQ(l["count"].get<uint64_t>(), 999u);
  EXPECT_EQ(l["unanswered"].get<uint64_t>(), 1u);
  EXPECT_EQ(j["lockstep"]["fallbacks"].get<uint64_t>(), 0u);
  expect_a_sane_distribution(l);
}

TEST(LoopLatencyE2E, AHeldHilLinkIsInEveryAnswer) {
  // hil-delay:30 holds each datagram to the board 30 ms: no answer can come sooner. (--speed 1:
  // at --speed 0 the session would run its whole duration before the first answer is back.)
  const auto j = sim_against_target(true, {"--duration", "0.5", "--speed", "1", "--fault", "hil-delay:30", "--lockstep-timeout", "2"});
  const auto& l = j["loop_latency"];
  EXPECT_EQ(l["sensors"].get<uint64_t>(), 125u) << l.dump();
  EXPECT_EQ(l["count"].get<uint64_t>() + l["unanswered"].get<uint64_t>(), 125u);
  EXPECT_GE(l["count"].get<uint64_t>(), 100u);
  EXPECT_GE(l["min_us"].get<double>(), 30000.0);
  uint64_t from_16_ms = 0;
  for (std::size_t i = 7; i < l["histogram"].size(); ++i) from_16_ms += l["histogram"][i]["count"].get<uint64_t>();
  EXPECT_EQ(from_16_ms, l["count"].get<uint64_t>()) << "every answer in the bins from 16 ms";
  expect_a_sane_distribution(l);
}

TEST(LoopLatencyE2E, RealTimeTakesTheNextActuatorMessage) {
  const auto j = sim_against_target(false, {"--duration", "2"});
  const auto& l = j["loop_latency"];
  EXPECT_EQ(l["matched"], "next");
  EXPECT_EQ(l["sensors"].get<uint64_t>(), 500u);
  EXPECT_EQ(l["count"].get<uint64_t>() + l["unanswered"].get<uint64_t>(), 500u);
  expect_a_sane_distribution(l);
}

}  // namespace
}  // namespace hitl
