// The vibration spectrum: a sinusoid's amplitude at its frequency, and a frequency above half the
// rate folded back below it.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/report/spectrum.h"

namespace hitl::report {
namespace {

std::vector<double> sinusoid(double amplitude, double freq_hz, double rate_hz, std::size_t n, double offset = 0) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = offset + amplitude * std::sin(2 * M_PI * freq_hz * static_cast<double>(i) / rate_hz);
  return v;
}

std::pair<double, double> peak(const AmplitudeSpectrum& s) {
  std::size_t best = 0;
  for (std::size_t k = 0; k < s.amplitude.size(); ++k)
    if (s.amplitude[k] > s.amplitude[best]) best = k;
  return {s.freq_hz[best], s.amplitude[best]};
}

TEST(Spectrum, ASinusoidsAmplitudeAtItsFrequencyAndNoOffset) {
  const auto s = amplitude_spectrum(sinusoid(8, 90, 250, 5000, -9.81), 250, 512);
  EXPECT_EQ(s.segments, 18u);  // (5000 - 512) / 256 + 1
  ASSERT_EQ(s.freq_hz.size(), 257u);
  EXPECT_DOUBLE_EQ(s.freq_hz.back(), 125.0);
  const auto [f_hz, a] = peak(s);
  EXPECT_NEAR(f_hz, 90, 0.5);
  EXPECT_NEAR(a, 8, 0.8) << "a bin's edge lowers a Hann window's peak by at most 15%";
  EXPECT_LT(s.amplitude[0], 0.1) << "each segment's mean removed: the -9.81 offset is not a vibration";
}

TEST(Spectrum, AboveHalfTheRateItFoldsBack) {
  const auto [f_hz, a] = peak(amplitude_spectrum(sinusoid(5, 150, 250, 4096), 250, 512));
  EXPECT_NEAR(f_hz, 100, 0.5);  // 250 - 150
  EXPECT_NEAR(a, 5, 0.5);
}

TEST(Spectrum, TooFewSamplesGiveNone) {
  EXPECT_TRUE(amplitude_spectrum(sinusoid(1, 10, 250, 100), 250, 512).freq_hz.empty());
  EXPECT_TRUE(amplitude_spectrum(sinusoid(1, 10, 250, 1000), 0, 512).freq_hz.empty());
}

TEST(Spectrum, TheRateIsOneOverTheMedianInterval) {
  EXPECT_NEAR(sample_rate_hz({0, 0.004, 0.008, 0.5, 0.504}), 250, 1e-9);
  EXPECT_EQ(sample_rate_hz({1}), 0);
}

}  // namespace
}  // namespace hitl::report
