// The rotors' vibration at the IMU: each rotor's line at its frequency, its blade-pass harmonic,
// both growing as the speed squared, averaged over each sample interval (sinc), or through the
// part's filter and sampled at its rate; the x500's default within PX4's vibration guidance.
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

Series shaken(const model::VibrationConfig& vibration, std::array<double, 4> rotor_speed_rad_s,
              const model::ImuFilterConfig& filter = {}) {
  model::ImuConfig config = model::with_noise_disabled(model::x500_vehicle_config()).sensors.imu;
  config.vibration = vibration;
  config.filter = filter;
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

TEST(AirframeVibration, OffWithoutCoefficientsAndWithTheRotorsStopped) {
  EXPECT_FALSE(AirframeVibration(model::VibrationConfig{}, 1).enabled());
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

TEST(AirframeVibration, MeanOfSamplesSpreadOverAnInterval) {
  for (const double n : {1.0, 2.0, 7.0, 32.0}) {
    for (const double d : {0.0, 0.4, 3.0, 2.0 * std::numbers::pi * n, 25.0}) {
      Eigen::Vector2d direct = Eigen::Vector2d::Zero();
      for (int k = 1; k <= static_cast<int>(n); ++k) direct += Eigen::Vector2d(std::cos(0.7 + k * d / n), std::sin(0.7 + k * d / n));
      direct /= n;
      const Eigen::Vector2d m = AirframeVibration::mean_cos_sin_sampled(0.7, d, n);
      EXPECT_NEAR(m.x(), direct.x(), 1e-12) << "n " << n << " d " << d;
      EXPECT_NEAR(m.y(), direct.y(), 1e-12) << "n " << n << " d " << d;
    }
  }
  // Many samples: the continuous mean.
  EXPECT_NEAR(AirframeVibration::mean_cos_sin_sampled(0.3, 1.2, 1e6).x(), AirframeVibration::mean_cos_sin(0.3, 1.2).x(), 1e-6);
}

TEST(AirframeVibration, ThePartsFilterIsDownThreeDecibelsAtItsBandwidths) {
  model::ImuFilterConfig f;
  EXPECT_EQ(AirframeVibration::filter_response(f, 5000.0), std::complex<double>(1.0));
  f.anti_alias_hz = 585.0;
  EXPECT_NEAR(std::abs(AirframeVibration::filter_response(f, 2.0 * std::numbers::pi * 585.0)), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(std::arg(AirframeVibration::filter_response(f, 2.0 * std::numbers::pi * 585.0)), -std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(std::abs(AirframeVibration::filter_response(f, 2.0 * std::numbers::pi * 5850.0)), 0.01, 1e-4);  // -40 dB/decade
  f.anti_alias_hz = 0.0;
  f.ui_filter_hz = 4000.0;
  EXPECT_NEAR(std::abs(AirframeVibration::filter_response(f, 2.0 * std::numbers::pi * 4000.0)), std::sqrt(0.5), 1e-12);
}

TEST(AirframeVibration, ThroughTheICM42688PsFilterAndSampledAtItsRate) {
  // PX4's ICM-42688-P setting: 8 kHz, 585 Hz anti-alias, 4 kHz first order; 32 samples per 4 ms.
  const model::ImuFilterConfig f{8000.0, 585.0, 4000.0};
  model::VibrationConfig v;
  v.imbalance_m_s2_per_rad2_s2 = 1e-5;
  v.blade_pass_m_s2_per_rad2_s2 = 4e-6;
  const double f_hz = 100.0, w = 2.0 * std::numbers::pi * f_hz;
  const Series s = shaken(v, {w, 0.0, 0.0, 0.0}, f);
  const auto sampled_mean = [](double line_hz) {  // |mean of 32 samples at 8 kHz| of a unit line
    return std::abs(std::sin(std::numbers::pi * line_hz * 32 / 8000.0) / (32 * std::sin(std::numbers::pi * line_hz / 8000.0)));
  };
  const double h1 = std::abs(AirframeVibration::filter_response(f, w));
  const double h2 = std::abs(AirframeVibration::filter_response(f, 2 * w));
  EXPECT_LT(h2, h1);
  EXPECT_NEAR(amplitude(s.accel_x, f_hz), 1e-5 * w * w * h1 * sampled_mean(f_hz), 1e-3);
  // The blade pass at 200 Hz, aliased to 50 Hz.
  EXPECT_NEAR(amplitude(s.accel_z, kRate_hz - 2 * f_hz), 4e-6 * w * w * h2 * sampled_mean(2 * f_hz), 1e-3);
}

TEST(AirframeVibration, TheX500ShakesAtItsHoverWithinPx4sGuidance) {
  // PX4's log-analysis guide: more than 2-3 m/s^2 peak to peak of raw acceleration is strong vibration.
  const model::VehicleConfig x500 = model::x500_vehicle_config();
  ASSERT_TRUE(AirframeVibration(x500.sensors.imu.vibration, 1).enabled());
  const model::WorldConfig world = model::default_world_config();
  const double hover_rad_s = std::sqrt(model::total_mass_kg(x500) * world.gravity_m_s2 / (4.0 * x500.rotors[0].motor_constant_N_s2));
  for (const std::uint64_t seed : {1, 2, 3}) {
    Imu imu(x500.sensors.imu, world, seed);  // with its noise
    model::VehicleState state;
    state.specific_force_FLU_m_s2 = {0.0, 0.0, 9.80665};
    state.rotor_speed_rad_s = {hover_rad_s, hover_rad_s, hover_rad_s, hover_rad_s};
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
    std::vector<double> accel_x, accel_z;
    for (int k = 1; k <= 10 * static_cast<int>(kRate_hz); ++k) {
      const Eigen::Vector3d a = imu.sample(state, k / kRate_hz).accel_FRD_m_s2;
      if (k > kRate_hz) {  // past the bias's first second
        lo = lo.cwiseMin(a);
        hi = hi.cwiseMax(a);
      }
      accel_x.push_back(a.x());
      accel_z.push_back(a.z());
    }
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_LT(hi[axis] - lo[axis], 2.0) << "seed " << seed << " axis " << axis;
      EXPECT_GT(hi[axis] - lo[axis], 0.1) << "seed " << seed << " axis " << axis;
    }
    // The rotor line, and the blade pass read at 250 - 2 f.
    const double f_hz = hover_rad_s / (2.0 * std::numbers::pi);
    EXPECT_GT(amplitude(accel_x, f_hz), 0.02) << "seed " << seed;
    EXPECT_GT(amplitude(accel_z, kRate_hz - 2.0 * f_hz), 0.02) << "seed " << seed;
  }
}

}  // namespace
}  // namespace hitl::sensors
