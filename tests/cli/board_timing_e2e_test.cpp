// hitl sim --board-timing voxl2 (issue 37 item 4): a lockstep hover against the emulated board with
// the board's data path delays on the sensors. It flies, the summary says what was applied, and
// the same seed gives the same figures.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"
#include "tests/support/tools.h"

namespace hitl::test {
namespace {

using namespace std::chrono_literals;

nlohmann::json hover(const std::string& timing) {
  const uint16_t hil = free_udp_port();
  Process board({hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
                 std::to_string(free_udp_port()), "--vio-port", "0", "--lockstep"});
  EXPECT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();
  Process sim({hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
               std::to_string(free_udp_port()), "--no-vio", "--clients", "0", "--lockstep", "--speed", "0", "-t",
               source_path("docs/examples/hover.json"), "--board-timing", timing, "--seed", "4"});
  const int code = sim.wait(120s);
  board.signal(SIGINT);
  board.wait(20s);
  EXPECT_EQ(code, 0) << sim.err();
  return last_json_line(sim.out());
}

TEST(BoardTiming, AHoverFliesWithTheVoxl2DataPathDelays) {
  const auto with = hover("voxl2");
  ASSERT_EQ(with["type"], "summary") << with.dump();
  EXPECT_EQ(with["trajectory"]["state"], "DONE") << with.dump();
  EXPECT_EQ(with["landing"]["touchdowns"], 1) << with.dump();
  const auto& t = with["board_timing"];
  ASSERT_TRUE(t.is_object()) << with.dump();
  EXPECT_EQ(t["model"], "voxl2");
  EXPECT_GT(t["imu_samples"].get<double>(), 5000);
  EXPECT_NEAR(t["imu_delay_mean_ms"].get<double>(), 4.0, 0.3);
  EXPECT_LT(t["imu_delay_max_ms"].get<double>(), 8.0);
  EXPECT_GT(t["mag_baro_samples"].get<double>(), 1000);
  EXPECT_LT(t["mag_baro_delay_max_ms"].get<double>(), 18.0);
  std::cout << "voxl2 timing: " << t.dump() << ", tracking RMS " << with["trajectory"]["rms_m"] << " m" << std::endl;

  const auto again = hover("voxl2");  // lockstep: the same seed, the same delays and flight
  EXPECT_EQ(again["board_timing"], t);
  EXPECT_EQ(again["trajectory"]["rms_m"], with["trajectory"]["rms_m"]);

  const auto without = hover("none");
  EXPECT_FALSE(without.contains("board_timing")) << without.dump();
  std::cout << "none: tracking RMS " << without["trajectory"]["rms_m"] << " m" << std::endl;
}

}  // namespace
}  // namespace hitl::test
