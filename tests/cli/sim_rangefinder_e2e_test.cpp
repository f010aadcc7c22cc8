// hitl sim's rangefinder (a sensor unit: engine/sensors/rangefinder) end to end, through the real
// binary over loopback: off by default; with --rangefinder, DISTANCE_SENSOR at its rate with the
// height above the ground as a climbing vehicle has it (HIL_GPS, noise-free, says the height);
// its faults change what it reports; from the vehicle file without the flag; a fault of a unit
// that is off is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "tests/cli/sim_board.h"

namespace hitl {
namespace {

using namespace sim_e2e;

constexpr double kHomeAlt_mm = 488000;  // the default world's home
constexpr double kMountBelowBase_cm = 5;  // the rangefinder's default mount

std::vector<msg::DistanceSensor> distances(const std::vector<mavlink::Frame>& frames) {
  std::vector<msg::DistanceSensor> out;
  for (const auto& f : frames)
    if (f.is<msg::DistanceSensor>()) out.push_back(f.as<msg::DistanceSensor>());
  return out;
}

TEST(SimRangefinderE2E, OffByDefault) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "1", "--speed", "0", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  board.stop();
  EXPECT_TRUE(distances(board.frames()).empty());
  EXPECT_FALSE(last_json(sim.out())["sent"].contains("DISTANCE_SENSOR"));
}

TEST(SimRangefinderE2E, SendsTheHeightAboveGroundAtItsRateWhileClimbingStuckHoldsIt) {
  Board board;
  // Armed a little above hover from the start: the x500 lifts off and climbs.
  board.serve([](const msg::HilSensor&, uint64_t) { return actuators(kHover * 1.05, true); });
  Process sim(board.sim_args({"--duration", "4", "--speed", "0", "--no-vio", "--no-noise", "--rangefinder",
                              "--fault", "rangefinder-stuck@2+1"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  board.stop();
  const auto frames = board.frames();
  const auto d = distances(frames);
  // 100 Hz of simulated time: at 4 ms (the first step), then due every 10 ms to 4 s, each sent
  // with the first 4 ms step at or after its due time (12, 20, 32, 40, 52, ... ms).
  ASSERT_EQ(d.size(), 401u);
  EXPECT_EQ(d[0].time_boot_ms, 4u);
  for (std::size_t i = 1; i < d.size(); ++i) EXPECT_EQ(d[i].time_boot_ms, (10 * i + 3) / 4 * 4) << i;
  std::map<uint32_t, msg::DistanceSensor> by_ms;
  for (const auto& m : d) {
    EXPECT_EQ(m.min_distance, 10);
    EXPECT_EQ(m.max_distance, 1200);
    EXPECT_EQ(m.orientation, 25);  // MAV_SENSOR_ROTATION_PITCH_270: downward
    EXPECT_EQ(m.type, 0);          // MAV_DISTANCE_SENSOR_LASER
    by_ms[m.time_boot_ms] = m;
  }
  // Against the height HIL_GPS reports in the same step (exact with --no-noise).
  const uint16_t held = std::prev(by_ms.lower_bound(2000))->second.current_distance;  // the last before the fault
  int compared = 0;
  double highest_cm = 0;
  for (const auto& f : frames) {
    if (!f.is<msg::HilGps>()) continue;
    const auto g = f.as<msg::HilGps>();
    const auto ms = static_cast<uint32_t>(g.time_usec / 1000);
    if (!by_ms.count(ms)) continue;
    const auto& m = by_ms.at(ms);
    if (ms >= 2000 && ms < 3000) {
      EXPECT_EQ(m.current_distance, held) << "stuck at t = " << ms << " ms";
      continue;
    }
    const double expected_cm = (g.alt - kHomeAlt_mm) / 10.0 - kMountBelowBase_cm;
    EXPECT_NEAR(m.current_distance, expected_cm, 1.0) << "t = " << ms << " ms";
    EXPECT_EQ(m.signal_quality, 100);
    highest_cm = std::max(highest_cm, expected_cm);
    ++compared;
  }
  EXPECT_GT(compared, 25);
  EXPECT_GT(highest_cm, 200) << "the vehicle climbed";
  EXPECT_NE(by_ms.at(3000).current_distance, held) << "live again when the fault ended";
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["sent"]["DISTANCE_SENSOR"]["count"], 401);
}

TEST(SimRangefinderE2E, FromTheVehicleFileAtItsRateNoReturnReportsOutOfRange) {
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/lidar.json") << R"({"sensors": {"rangefinder": {"enabled": true, "rate_hz": 50}}})";
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "3", "--speed", "0", "--no-vio", "--vehicle", dir + "/lidar.json",
                              "--fault", "rangefinder-no-return@1+1"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  board.stop();
  const auto d = distances(board.frames());
  EXPECT_EQ(d.size(), 151u);  // 50 Hz for 3 s, and the first step's
  double sum_cm = 0;
  int resting = 0;
  for (const auto& m : d) {
    if (m.time_boot_ms >= 1000 && m.time_boot_ms < 2000) {
      EXPECT_EQ(m.current_distance, 1201) << m.time_boot_ms;  // max + 1 cm: no valid return
      EXPECT_EQ(m.signal_quality, 1);
    } else {
      EXPECT_EQ(m.signal_quality, 100);
      EXPECT_NEAR(m.current_distance, 17, 10) << m.time_boot_ms;  // at rest: the mount ~17 cm up, sigma 2.5 cm
      sum_cm += m.current_distance;
      ++resting;
    }
  }
  ASSERT_GT(resting, 90);
  EXPECT_NEAR(sum_cm / resting, 17, 1.0) << "the mean at rest";
}

TEST(SimRangefinderE2E, AFaultOfAUnitThatIsOffIsRefused) {
  Board board;
  Process sim(board.sim_args({"--duration", "1", "--speed", "0", "--no-vio", "--fault", "rangefinder-stuck@1"}));
  EXPECT_EQ(sim.wait(30s), 2);
  EXPECT_NE(sim.err().find("fault rangefinder-stuck: the rangefinder is off; turn it on with --rangefinder"), std::string::npos)
      << sim.err();
}

}  // namespace
}  // namespace hitl
