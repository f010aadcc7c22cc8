// The rotors' vibration at the IMU: each rotor's line at its frequency, its blade-pass harmonic,
// both growing as the speed squared, averaged over each sample interval (sinc), off by default.
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "engine/model/x500_defaults.h"
#include "engine/sensors/imu.h"

namespace hitl::sensors {
namespace {

constexpr double kRate_hz = 250.0;
constexpr int kSamples = 1000;  // 4 s: whole cycles of every line below

/// The amplitude of the line at f_hz in x (one DFT bin).
double amplitude(const std::vector<double>& x, double f_hz) {
  std::complex<double> sum = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k)
    sum += x[k] * std::exp(std::complex<double>(0.0, -2.0 * std::numbers::pi * f_hz * static_cast<double>(k) / kRate_hz));
  return 2.0 * std::abs(sum) / static_cast<double>(x.size());
}

double sinc(double x) { return std::sin(x) / x; }

struct Series {
  std::vector<double> accel_x, accel_z, gyro_x;
};

Series shaken(const model::VibrationConfig& vibration, std::array<double, 4> rotor_speed_rad_s) {
  model::ImuConfig config = model::with_noise_disabled(model::x500_vehicle_config()).sensors.imu;
  config.vibration = vibration;
  Imu imu(config, model::default_world_config(), 3);
  model::VehicleState state;
  state.specific_force_FLU_m_s2 = {0.0, 0.0, 9.80665};
  state.rotor_speed_rad_s = rotor_speed_rad_s;
  Series s;
  for (int k = 1; k <= kSamples; ++k) {
    const ImuSample sample = imu.sample(state, k / kRate_hz);
    s.accel_x.push_back(sample.accel_FRD_m_s2.x());
    s.accel_z.push_back(sample.accel_FRD_m_s2.z());
    s.gyro_x.push_back(sample.gyro_FRD_rad_s.x());
  }
  return s;
}

TEST(AirframeVibration, ARotorsLineAtItsFrequencyGrowsAsItsSpeedSquared) {
  model::VibrationConfig v;
  v.imbalance_m_s2_per_rad2_s2 = 1e-5;
  v.blade_pass_m_s2_per_rad2_s2 = 4e-6;
  v.gyro_imbalance_rad_s_per_rad2_s2 = 1e-7;
  v.blades = 2;
  const double f_hz = 80.0, w = 2.0 * std::numbers::pi * f_hz;  // rotor 0 alone
  const double T = 1.0 / kRate_hz;
  const Series one = shaken(v, {w, 0.0, 0.0, 0.0});
  // The mean over each 4 ms interval: amplitude x sinc(pi f T).
  EXPECT_NEAR(amplitude(one.accel_x, f_hz), 1e-5 * w * w * sinc(std::numbers::pi * f_hz * T), 1e-3);
  EXPECT_NEAR(amplitude(one.gyro_x, f_hz), 1e-7 * w * w * sinc(std::numbers::pi * f_hz * T), 1e-4);
  // The blade pass at 160 Hz, above Nyquist (125 Hz): aliased to 90 Hz, attenuated by its sinc.
  EXPECT_NEAR(amplitude(one.accel_z, kRate_hz - 2 * f_hz), 4e-6 * w * w * std::abs(sinc(std::numbers::pi * 2 * f_hz * T)), 1e-3);
  EXPECT_LT(amplitude(one.accel_x, 40.0), 1e-6);  // nothing elsewhere
  // Half the speed (40 Hz): a quarter of the force, a milder sinc.
  const Series half = shaken(v, {w / 2, 0.0, 0.0, 0.0});
  EXPECT_NEAR(amplitude(half.accel_x, f_hz / 2), 1e-5 * w * w / 4 * sinc(std::numbers::pi * f_hz / 2 * T), 1e-3);
}

TEST(AirframeVibration, EachRotorHasItsOwnLine) {
  model::VibrationConfig v;
  v.imbalance_m_s2_per_rad2_s2 = 1e-5;
  const double w0 = 2.0 * std::numbers::pi * 60.0, w3 = 2.0 * std::numbers::pi * 70.0;
  const Series s = shaken(v, {w0, 0.0, 0.0, w3});
  EXPECT_GT(amplitude(s.accel_x, 60.0), 0.5 * 1e-5 * w0 * w0);
  EXPECT_GT(amplitude(s.accel_x, 70.0), 0.5 * 1e-5 * w3 * w3);
}

TEST(AirframeVibration, OffByDefaultAndWithTheRotorsStopped) {
  EXPECT_FALSE(AirframeVibration(model::x500_vehicle_config().sensors.imu.vibration, 1).enabled());
  const Series still = shaken(model::VibrationConfig{}, {900.0, 900.0, 900.0, 900.0});
  for (double a : still.accel_x) EXPECT_EQ(a, 0.0);
  model::VibrationConfig v;
  v.imbalance_m_s2_per_rad2_s2 = 1e-5;
  const Series stopped = shaken(v, {0.0, 0.0, 0.0, 0.0});
  for (double a : stopped.accel_x) EXPECT_EQ(a, 0.0);
}

TEST(AirframeVibration, MeanOfCosAndSinOverAnInterval) {
  const Eigen::Vector2d m = AirframeVibration::mean_cos_sin(0.3, 1.2);
  EXPECT_NEAR(m.x(), (std::sin(1.5) - std::sin(0.3)) / 1.2, 1e-15);
  EXPECT_NEAR(m.y(), (std::cos(0.3) - std::cos(1.5)) / 1.2, 1e-15);
  EXPECT_NEAR(AirframeVibration::mean_cos_sin(0.3, 0.0).x(), std::cos(0.3), 1e-15);
}

}  // namespace
}  // namespace hitl::sensors
