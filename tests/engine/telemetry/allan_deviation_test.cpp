// The overlapping Allan deviation on synthetic series whose answers are known analytically:
// white noise (adev = N / sqrt(tau), N = sigma / sqrt(rate)) and a rate random walk
// (adev = K sqrt(tau / 3)).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/telemetry/allan_deviation.h"

namespace hitl::telemetry {
namespace {

constexpr double kRate_hz = 250.0;

std::vector<double> white(std::size_t n, double sigma, double offset, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> out(n);
  for (double& x : out) x = offset + normal(rng);
  return out;
}

const AllanPoint& nearest(const std::vector<AllanPoint>& curve, double tau_s) {
  const AllanPoint* best = &curve.front();
  for (const AllanPoint& p : curve)
    if (std::abs(std::log(p.tau_s / tau_s)) < std::abs(std::log(best->tau_s / tau_s))) best = &p;
  return *best;
}

TEST(AllanDeviation, WhiteNoiseFallsAsOneOverSqrtTauFromItsDensity) {
  const double noise_density = 4.9e-5;  // the ICM-42688-P's gyro, rad/s/sqrt(Hz)
  // A constant like gravity under the noise changes nothing.
  const auto samples = white(150000, noise_density * std::sqrt(kRate_hz), -9.80665, 7);
  const auto curve = overlapping_allan_deviation(samples, kRate_hz);
  ASSERT_GT(curve.size(), 30u);
  EXPECT_DOUBLE_EQ(curve.front().tau_s, 1.0 / kRate_hz);
  EXPECT_LE(curve.back().cluster_samples, 15000u);  // at most n / 10, 10 per decade
  EXPECT_GT(curve.back().cluster_samples, 11000u);
  for (double tau_s : {0.004, 0.1, 1.0, 10.0}) {
    EXPECT_NEAR(nearest(curve, tau_s).deviation / (noise_density / std::sqrt(nearest(curve, tau_s).tau_s)), 1.0, 0.1)
        << "tau " << tau_s;
  }
  const AllanFit fit = fit_allan(curve);
  EXPECT_NEAR(fit.noise_density / noise_density, 1.0, 0.05);
  // No floor: the minimum is at the long end, about N / sqrt(tau) there.
  EXPECT_GT(fit.minimum_tau_s, 20.0);
  EXPECT_NEAR(fit.bias_instability * 0.664 / (noise_density / std::sqrt(fit.minimum_tau_s)), 1.0, 0.3);
}

TEST(AllanDeviation, RateRandomWalkRisesAsSqrtTauOverThree) {
  const double random_walk = 1e-3;  // K, unit/s/sqrt(Hz)
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, random_walk * std::sqrt(1.0 / kRate_hz));
  std::vector<double> samples(150000);
  double x = 0.0;
  for (double& s : samples) s = (x += normal(rng));
  const auto curve = overlapping_allan_deviation(samples, kRate_hz);
  for (double tau_s : {1.0, 5.0, 20.0}) {
    const AllanPoint& p = nearest(curve, tau_s);
    EXPECT_NEAR(p.deviation / (random_walk * std::sqrt(p.tau_s / 3.0)), 1.0, 0.25) << "tau " << tau_s;
  }
}

TEST(AllanDeviation, WhiteNoiseAndRandomWalkMeetAtTheAnalyticMinimum) {
  // adev^2 = N^2 / tau + K^2 tau / 3: minimum at tau = sqrt(3) N / K, of 2 N K / sqrt(3).
  const double noise_density = 0.004;
  const double random_walk = 0.006;  // the generic accelerometer's
  std::mt19937_64 rng(3);
  std::normal_distribution<double> walk(0.0, random_walk * std::sqrt(1.0 / kRate_hz));
  std::normal_distribution<double> white_noise(0.0, noise_density * std::sqrt(kRate_hz));
  std::vector<double> samples(150000);
  double bias = 0.0;
  for (double& s : samples) s = (bias += walk(rng)) + white_noise(rng);
  const AllanFit fit = fit_allan(overlapping_allan_deviation(samples, kRate_hz));
  EXPECT_NEAR(fit.noise_density / noise_density, 1.0, 0.1);
  const double minimum = std::sqrt(2.0 * noise_density * random_walk / std::sqrt(3.0));
  EXPECT_NEAR(fit.bias_instability * 0.664 / minimum, 1.0, 0.25);
  EXPECT_NEAR(fit.minimum_tau_s / (std::sqrt(3.0) * noise_density / random_walk), 1.0, 0.6);
}

TEST(AllanDeviation, ShortOrConstantSeries) {
  EXPECT_TRUE(overlapping_allan_deviation(std::vector<double>(kAllanMinSamples - 1, 1.0), kRate_hz).empty());
  EXPECT_TRUE(overlapping_allan_deviation(std::vector<double>(1000, 1.0), 0.0).empty());
  const auto flat = overlapping_allan_deviation(std::vector<double>(1000, 3.0), kRate_hz);
  ASSERT_FALSE(flat.empty());
  const AllanFit fit = fit_allan(flat);
  EXPECT_EQ(fit.bias_instability, 0.0);
  EXPECT_EQ(fit.noise_density, 0.0);
  EXPECT_EQ(fit_allan({}).fit_points, 0u);
}

}  // namespace
}  // namespace hitl::telemetry
