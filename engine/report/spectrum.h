// The vibration spectrum the report draws (docs/report.md "Vibration"): Welch's method on a
// sampled signal with Eigen's FFT (unsupported/Eigen/FFT, shipped with libeigen3-dev).
#pragma once

#include <cstddef>
#include <vector>

namespace hitl::report {

struct AmplitudeSpectrum {
  std::vector<double> freq_hz;    ///< 0 .. rate/2, rate / segment apart
  std::vector<double> amplitude;  ///< the amplitude of a sinusoid at that frequency (the signal's unit), RMS over the segments
  std::size_t segments = 0;
};

/// Segments of `segment` samples, each half over the one before, their mean removed and a Hann
/// window applied; |X|^2 averaged over them; a sinusoid of amplitude A at a bin's frequency gives A
/// (2 |X| / the window's sum). Empty when there are fewer than `segment` samples.
AmplitudeSpectrum amplitude_spectrum(const std::vector<double>& samples, double rate_hz, std::size_t segment = 512);

/// The rate of samples at `t_s` (seconds, ascending): 1 / the median interval; 0 with fewer than 2.
double sample_rate_hz(const std::vector<double>& t_s);

}  // namespace hitl::report
