// Absolute-time sample scheduling against the 4 ms physics step.
#include "engine/sensors/scheduler.h"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace hitl::sensors {
namespace {

TEST(Scheduler, LongRunRatesAreExact) {
  SensorScheduler scheduler(250.0, 50.0, 10.0, 30.0);
  int imu = 0, mag = 0, baro = 0, gps = 0;
  std::vector<double> gps_times;
  const int steps = 15000;  // 60 s of 4 ms steps
  for (int n = 1; n <= steps; ++n) {
    const double t = n * 0.004;
    const DueSensors due = scheduler.due(t);
    imu += due.imu;
    mag += due.mag;
    baro += due.baro;
    gps += due.gps;
    if (due.gps) gps_times.push_back(t);
  }
  // Samples k / rate for k = 0 .. 60 * rate, the first one taken at the first step.
  EXPECT_EQ(imu, 15000);
  EXPECT_EQ(mag, 3001);
  EXPECT_EQ(baro, 601);
  EXPECT_EQ(gps, 1801);
  // Every GPS sample within one step after its due time (1/30 s is not a multiple of 4 ms).
  for (std::size_t k = 1; k < gps_times.size(); ++k) {
    const double due_s = static_cast<double>(k) / 30.0;
    EXPECT_GE(gps_times[k], due_s - 1e-9) << k;
    EXPECT_LT(gps_times[k], due_s + 0.004) << k;
  }
}

TEST(Scheduler, MagEveryFifthStepBaroEveryTwentyFifth) {
  PeriodicSchedule mag(50.0), baro(10.0);
  for (int n = 1; n <= 100; ++n) {
    const double t = n * 0.004;
    EXPECT_EQ(mag.due(t), n == 1 || n % 5 == 0) << n;
    EXPECT_EQ(baro.due(t), n == 1 || n % 25 == 0) << n;
  }
}

TEST(Scheduler, MissedPeriodsGiveOneSampleNotABurst) {
  PeriodicSchedule s(100.0);
  EXPECT_TRUE(s.due(0.0));
  EXPECT_TRUE(s.due(0.5));  // 49 periods late: one sample
  EXPECT_FALSE(s.due(0.5));
  EXPECT_NEAR(s.next_due_s(), 0.51, 1e-12);
  s.reset();
  EXPECT_TRUE(s.due(0.0));
}

}  // namespace
}  // namespace hitl::sensors
