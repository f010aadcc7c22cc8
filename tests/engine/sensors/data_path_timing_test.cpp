// The board's data path timing (engine/sensors/data_path_timing.h): the delays the spec's HIL split
// and dsp_hitl put on each sample, applied to what the session sends.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/sensors/data_path_timing.h"

namespace hitl::sensors {
namespace {

constexpr double kStep_s = 0.004;

/// A frame at step k: the IMU every step, reading a ramp (accel x = time, gyro z = 2 time), the
/// magnetometer and barometer every `mag_baro_every` steps.
SensorFrame frame_at(int k, int mag_baro_every = 3) {
  const double t = k * kStep_s;
  SensorFrame f;
  ImuSample imu;
  imu.time_s = t;
  imu.accel_FRD_m_s2 = {t, 0.0, -9.81};
  imu.gyro_FRD_rad_s = {0.0, 0.0, 2.0 * t};
  f.imu = imu;
  if (k % mag_baro_every == 0) {
    MagSample m;
    m.time_s = t;
    m.mag_FRD_gauss = {t, 0.0, 0.0};
    f.mag = m;
    BaroSample b;
    b.time_s = t;
    b.pressure_Pa = 101325.0 - t;
    f.baro = b;
  }
  return f;
}

TEST(DataPathTiming, TheImuArrivesUpToEightMillisecondsLateAndFourOnAverage) {
  DataPathTiming timing(*data_path_timing_model("voxl2"), 7);
  double sum_s = 0, max_s = 0, min_s = 1;
  int n = 0;
  for (int k = 0; k < 25000; ++k) {  // 100 s at 250 Hz
    SensorFrame f = frame_at(k);
    const double now_s = k * kStep_s;
    timing.apply(f, now_s);
    ASSERT_TRUE(f.imu);
    const double delay_s = now_s - f.imu->time_s;
    // The sample is the ramp at its own (earlier) time: linear between the steps around it.
    EXPECT_NEAR(f.imu->accel_FRD_m_s2.x(), f.imu->time_s, 1e-12);
    EXPECT_NEAR(f.imu->gyro_FRD_rad_s.z(), 2.0 * f.imu->time_s, 1e-12);
    if (k < 3) continue;  // the first steps have no earlier sample to reach back to
    sum_s += delay_s;
    max_s = std::max(max_s, delay_s);
    min_s = std::min(min_s, delay_s);
    ++n;
  }
  EXPECT_NEAR(sum_s / n, 0.004, 0.0001);  // U(0,4 ms) + U(0,4 ms)
  EXPECT_LT(max_s, 0.008);
  EXPECT_GT(max_s, 0.0075);
  EXPECT_GE(min_s, 0.0);
  EXPECT_LT(min_s, 0.0005);
  const auto& fig = timing.figures();
  EXPECT_EQ(fig.imu_samples, 25000u);
  EXPECT_NEAR(fig.imu_delay_mean_s, 0.004, 0.0001);
}

TEST(DataPathTiming, MagAndBaroArriveWhenTheirDelayHasPassedTheNewestFirst) {
  DataPathTiming timing(*data_path_timing_model("voxl2"), 3);
  double last_mag_time_s = -1;
  int delivered = 0, sampled = 0;
  for (int k = 0; k < 7500; ++k) {  // 30 s; mag/baro at 83 Hz (every 3 steps)
    SensorFrame f = frame_at(k);
    if (f.mag) ++sampled;
    const double now_s = k * kStep_s;
    timing.apply(f, now_s);
    if (!f.mag) continue;
    ++delivered;
    const double delay_s = now_s - f.mag->time_s;
    EXPECT_GE(delay_s, 0.0);
    EXPECT_LT(delay_s, 0.014 + kStep_s);  // due within 10 + 4 ms, sent at the next step
    EXPECT_GT(f.mag->time_s, last_mag_time_s);  // never an older sample after a newer one
    EXPECT_DOUBLE_EQ(f.mag->mag_FRD_gauss.x(), f.mag->time_s);  // a sample as taken, not interpolated
    last_mag_time_s = f.mag->time_s;
  }
  EXPECT_GT(delivered, sampled * 9 / 10);  // a few overtaken by the next one, as the split's newest-wins
  EXPECT_LE(delivered, sampled);
  EXPECT_NEAR(timing.figures().mag_baro_delay_mean_s, 0.007 + kStep_s / 2, 0.002);
}

TEST(DataPathTiming, TheSameSeedGivesTheSameDelaysAndAResetRepeatsThem) {
  DataPathTiming a(*data_path_timing_model("voxl2"), 11), b(*data_path_timing_model("voxl2"), 11),
      c(*data_path_timing_model("voxl2"), 12);
  std::vector<double> first, other;
  for (int k = 0; k < 500; ++k) {
    SensorFrame fa = frame_at(k), fb = frame_at(k), fc = frame_at(k);
    a.apply(fa, k * kStep_s);
    b.apply(fb, k * kStep_s);
    c.apply(fc, k * kStep_s);
    EXPECT_EQ(fa.imu->time_s, fb.imu->time_s);
    first.push_back(fa.imu->time_s);
    other.push_back(fc.imu->time_s);
  }
  EXPECT_NE(first, other);
  a.reset();
  for (int k = 0; k < 500; ++k) {
    SensorFrame f = frame_at(k);
    a.apply(f, k * kStep_s);
    EXPECT_EQ(f.imu->time_s, first[static_cast<std::size_t>(k)]) << k;
  }
}

TEST(DataPathTiming, HoldsOnlyWhatALaterDelayCanReach) {
  DataPathTiming timing(*data_path_timing_model("voxl2"), 1);
  for (int k = 0; k < 100000; ++k) {
    SensorFrame f = frame_at(k, 1);  // mag/baro every step: more than the split publishes
    timing.apply(f, k * kStep_s);
  }
  // Bounded: what is held does not grow with the run (checked through the delays staying in range).
  EXPECT_LT(timing.figures().imu_delay_max_s, 0.008);
  EXPECT_LT(timing.figures().mag_baro_delay_max_s, 0.014 + kStep_s);
  EXPECT_FALSE(data_path_timing_model("none"));
  EXPECT_FALSE(data_path_timing_model("VOXL2"));
}

}  // namespace
}  // namespace hitl::sensors
