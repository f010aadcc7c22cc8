// actuators-stale in the session (docs/faults.md): the board's actuator stream goes stale, the
// model holds the last commands it had. A stand-in board answers each HIL_SENSOR in lockstep with
// 0.9 on every motor until 1 s, then 0.3, and reads the thrust back off the HIL_SENSORs it gets
// (noise off: zacc is the rotors' thrust over the mass, less drag): under the fault the thrust
// stays 0.9's while the board asks for 0.3, and follows it from the step after the fault ends.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/engine/hil/lockstep_board.h"

namespace hitl::hil {
namespace {

using test_lockstep::mean_over;

constexpr double kBefore = 0.9, kAfter = 0.3;  ///< the board's command before and after 1 s

double command(uint64_t time_us) { return time_us < 1'000'000 ? kBefore : kAfter; }
double zacc(const mavlink::msg::HilSensor& s) { return s.zacc; }

TEST(ActuatorsStale, TheThrustStaysTheLastCommandsWhileTheBoardAsksForLessAndFollowsAfter) {
  const auto seen = test_lockstep::fly({"actuators-stale@0.5+0.8"}, 1.8, command);  // 0.5 .. 1.3 s
  const double held = mean_over(seen.sensors, 0.6, 1.0, zacc);    // the board asks for 0.9, the model has it
  const double stale = mean_over(seen.sensors, 1.05, 1.3, zacc);  // the board asks for 0.3, the model holds 0.9
  const double after = mean_over(seen.sensors, 1.4, 1.8, zacc);   // the fault over: 0.3
  std::printf("zacc (m/s^2): 0.9 commanded %.2f, 0.3 commanded but stale %.2f, 0.3 after the fault %.2f\n", held, stale, after);
  EXPECT_LT(held, -10.0);  // 0.9: thrust 4 kF (900 rad/s)^2 = 27.7 N on about 2 kg
  EXPECT_LT(stale, -10.0) << "the thrust must not follow the board's new command while stale";
  EXPECT_GT(after, -4.0);  // 0.3: 3.1 N
}

TEST(ActuatorsStale, WithoutItTheThrustFollowsTheBoard) {
  const auto seen = test_lockstep::fly({}, 1.8, command);
  EXPECT_LT(mean_over(seen.sensors, 0.6, 1.0, zacc), -10.0);
  EXPECT_GT(mean_over(seen.sensors, 1.05, 1.3, zacc), -4.0);
}

}  // namespace
}  // namespace hitl::hil
