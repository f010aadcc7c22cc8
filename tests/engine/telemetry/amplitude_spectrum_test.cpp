// The Welch amplitude spectrum on synthetic series whose answers are known: a sine reads its
// frequency and amplitude (on a bin and between bins), two sines their two lines, a constant (gravity)
// nothing, a short series no curve; the decimated curve keeps a line's peak.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "engine/telemetry/amplitude_spectrum.h"

namespace hitl::telemetry {
namespace {

constexpr double kRate_hz = 250.0;

std::vector<double> sines(std::size_t n, const std::vector<std::pair<double, double>>& amplitude_at_hz, double offset,
                          double noise_sigma = 0.0, double rate_hz = kRate_hz) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, noise_sigma > 0.0 ? noise_sigma : 1.0);
  std::vector<double> out(n, offset);
  for (std::size_t i = 0; i < n; ++i) {
    const double t_s = static_cast<double>(i) / rate_hz;
    for (const auto& [a, f] : amplitude_at_hz) out[i] += a * std::cos(2.0 * std::numbers::pi * f * t_s + 0.3);
    if (noise_sigma > 0.0) out[i] += normal(rng);
  }
  return out;
}

TEST(AmplitudeSpectrum, ASineOnABinReadsItsFrequencyAndAmplitude) {
  const auto s = welch_amplitude_spectrum(sines(5000, {{0.5, 40.0}}, -9.80665), kRate_hz, 250, 5);
  ASSERT_EQ(s.curve.size(), 126u);  // 0 .. 125 Hz
  EXPECT_DOUBLE_EQ(s.resolution_hz, 1.0);
  EXPECT_EQ(s.segments, 39u);  // (5000 - 250) / 125 + 1
  EXPECT_NEAR(s.curve[40].amplitude, 0.5, 0.5 * 0.01);
  ASSERT_FALSE(s.peaks.empty());
  EXPECT_NEAR(s.peaks[0].frequency_hz, 40.0, 0.05);
  EXPECT_NEAR(s.peaks[0].amplitude, 0.5, 0.5 * 0.01);
  EXPECT_LT(s.curve[0].amplitude, 1e-9);  // gravity, a constant, is removed
}

TEST(AmplitudeSpectrum, ASineBetweenBinsKeepsItsAmplitudeInThePeak) {
  // 122.5 Hz: the x500's hover rotor line, half a bin off and 2.5 Hz under Nyquist.
  const auto s = welch_amplitude_spectrum(sines(5000, {{0.2, 122.5}}, 0.0), kRate_hz, 250, 5);
  ASSERT_FALSE(s.peaks.empty());
  EXPECT_NEAR(s.peaks[0].frequency_hz, 122.5, 0.3);
  EXPECT_NEAR(s.peaks[0].amplitude, 0.2, 0.2 * 0.03);
  // The curve itself shows the Hann window's scalloping there (~0.85 of it).
  EXPECT_LT(s.curve[122].amplitude, 0.9 * 0.2);
}

TEST(AmplitudeSpectrum, TwoLinesInNoiseAreTheTwoStrongestPeaks) {
  const auto s = welch_amplitude_spectrum(sines(15000, {{0.3, 17.3}, {1.0, 81.0}}, 0.0, 0.05), kRate_hz, 250, 5);
  ASSERT_GE(s.peaks.size(), 2u);
  EXPECT_NEAR(s.peaks[0].frequency_hz, 81.0, 0.1);
  EXPECT_NEAR(s.peaks[0].amplitude, 1.0, 0.03);
  EXPECT_NEAR(s.peaks[1].frequency_hz, 17.3, 0.2);
  EXPECT_NEAR(s.peaks[1].amplitude, 0.3, 0.3 * 0.03);
  EXPECT_LT(s.peaks[2].amplitude, 0.05);
}

TEST(AmplitudeSpectrum, TooShortASeriesHasNoCurve) {
  EXPECT_TRUE(welch_amplitude_spectrum(sines(249, {{1.0, 10.0}}, 0.0), kRate_hz, 250, 5).curve.empty());
  EXPECT_TRUE(welch_amplitude_spectrum(sines(100, {{1.0, 10.0}}, 0.0), 0.0, 50, 5).curve.empty());
  EXPECT_EQ(welch_amplitude_spectrum(sines(250, {{1.0, 10.0}}, 0.0), kRate_hz, 250, 5).segments, 1u);
}

TEST(AmplitudeSpectrum, DecimationKeepsTheLine) {
  const auto s = welch_amplitude_spectrum(sines(20000, {{1.0, 333.0}}, 0.0, 0.0, 1000.0), 1000.0, 1000, 5);
  ASSERT_EQ(s.curve.size(), 501u);
  const auto d = decimate_spectrum(s.curve, 100);
  EXPECT_LE(d.size(), 100u);
  double best = 0.0, at_hz = 0.0;
  for (const auto& p : d)
    if (p.amplitude > best) best = p.amplitude, at_hz = p.frequency_hz;
  EXPECT_NEAR(best, 1.0, 0.01);
  EXPECT_NEAR(at_hz, 333.0, 0.01);
  EXPECT_EQ(decimate_spectrum(s.curve, 1000).size(), 501u);
}

}  // namespace
}  // namespace hitl::telemetry
