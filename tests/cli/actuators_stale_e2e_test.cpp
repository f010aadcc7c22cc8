// actuators-stale through the real hitl sim (docs/faults.md): the board's actuator stream goes
// stale, the model holds the last commands it had. A stand-in board answers each HIL_SENSOR in
// lockstep with 0.9 on every motor until 1 s of simulated time, then 0.3: under the fault the
// rotors stay at 0.9's speed while the board asks for 0.3, and follow it once the fault ends.
#include <gtest/gtest.h>

#include "tests/cli/sim_board.h"

namespace hitl {
namespace {

using namespace sim_e2e;

constexpr double kBefore = 0.9, kAfter = 0.3;  ///< the board's command before and after 1 s

/// hitl sim in lockstep against the stand-in board to `duration` with `fault`; its JSON summary.
nlohmann::json fly(const std::string& duration, const std::string& fault) {
  Board board;
  board.serve([](const msg::HilSensor& s, uint64_t) -> std::optional<msg::HilActuatorControls> {
    auto a = actuators(s.time_usec < 1'000'000 ? kBefore : kAfter, true);
    a.time_usec = s.time_usec;  // lockstep: the answer to this HIL_SENSOR
    return a;
  });
  std::vector<std::string> extra{"--duration", duration, "--speed", "2", "--lockstep", "--no-vio"};
  if (!fault.empty()) extra.insert(extra.end(), {"--fault", fault});
  std::vector<std::string> argv = board.sim_args({});
  argv.insert(argv.end(), extra.begin(), extra.end());
  Process sim(argv);
  EXPECT_EQ(sim.wait(30s), 0) << sim.err();
  return last_json(sim.out());
}

double scaling_rad_s() { return model::x500_vehicle_config().rotors[0].input_scaling_rad_s; }

TEST(ActuatorsStaleE2E, TheModelHoldsTheLastCommandsWhileTheBoardAsksForLess) {
  const auto j = fly("1.5", "actuators-stale@0.5");
  ASSERT_EQ(j.value("type", ""), "summary");
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(j["motor_commands"][i].get<double>(), kAfter, 1e-6) << "what the board asks for";
    EXPECT_NEAR(j["rotor_speed_rad_s"][i].get<double>(), kBefore * scaling_rad_s(), 1.0) << "what the model held, motor " << i;
  }
  EXPECT_EQ(j["active_faults"], nlohmann::json::array({"actuators-stale"}));
}

TEST(ActuatorsStaleE2E, TheRotorsFollowTheBoardAgainWhenItEnds) {
  const auto j = fly("1.8", "actuators-stale@0.5+0.8");  // ends at 1.3 s
  ASSERT_EQ(j.value("type", ""), "summary");
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(j["motor_commands"][i].get<double>(), kAfter, 1e-6);
    EXPECT_NEAR(j["rotor_speed_rad_s"][i].get<double>(), kAfter * scaling_rad_s(), 1.0) << "motor " << i;
  }
  ASSERT_EQ(j["faults"].size(), 1u);
  EXPECT_NEAR(j["faults"][0]["end_s"].get<double>(), 1.3, 1e-6);
}

TEST(ActuatorsStaleE2E, WithoutItTheRotorsFollowTheBoard) {
  const auto j = fly("1.5", "");
  ASSERT_EQ(j.value("type", ""), "summary");
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(j["rotor_speed_rad_s"][i].get<double>(), kAfter * scaling_rad_s(), 1.0) << "motor " << i;
}

}  // namespace
}  // namespace hitl
