// The amplitude spectrum of a sensor's samples, Welch-averaged: segments of `segment_samples`
// overlapping by half, each with its mean removed and a Hann window applied, transformed (Eigen's
// unsupported FFT module, kissfft inside), their powers averaged, then
//   amplitude(f_k) = 2 sqrt(mean |X_k|^2) / sum(w),   f_k = k rate / segment_samples, k = 0 .. N/2
// so a sine of amplitude A centred on a bin reads A there (the curve). A peak is a bin k >= 1 that
// is the largest within +-2 bins (its main lobe: a noise bump on a line's flank is no peak); its frequency is refined by a parabola through the log amplitudes of its bin and its
// neighbours, and its amplitude is read from the energy of its Hann main lobe (bins k-2 .. k+2):
//   A = 2 sqrt(sum mean |X_j|^2 / (N sum w^2))
// which is right for a sine anywhere between bins (no scalloping loss). Pure functions: no I/O.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace hitl::telemetry {

struct SpectrumPoint {
  double frequency_hz = 0.0;
  double amplitude = 0.0;  ///< in the samples' unit (a sine's amplitude, not RMS)
};

struct AmplitudeSpectrum {
  std::vector<SpectrumPoint> curve;  ///< bins 0 .. N/2
  std::vector<SpectrumPoint> peaks;  ///< the strongest first
  std::size_t segment_samples = 0;
  std::size_t segments = 0;
  double resolution_hz = 0.0;        ///< rate / segment_samples
};

/// The spectrum of `samples` at `rate_hz` with segments of `segment_samples` (at least 8), keeping
/// the `max_peaks` strongest peaks. Empty (no curve) when there are fewer samples than one segment.
AmplitudeSpectrum welch_amplitude_spectrum(std::span<const double> samples, double rate_hz, std::size_t segment_samples,
                                           std::size_t max_peaks);

/// At most `max_points` points of `curve`: consecutive bins grouped, each group shown by its
/// largest amplitude (a line is never averaged away) at that bin's frequency.
std::vector<SpectrumPoint> decimate_spectrum(std::span<const SpectrumPoint> curve, std::size_t max_points);

}  // namespace hitl::telemetry
