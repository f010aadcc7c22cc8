#include "cli/inspect_spectrum.h"

#include <cmath>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "engine/telemetry/imu_spectrum.h"

namespace hitl::cli {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

nlohmann::json window_json(const telemetry::ImuWindow& window) {
  return {{"from_s", window.from_s}, {"to_s", std::isfinite(window.to_s) ? nlohmann::json(window.to_s) : nlohmann::json(nullptr)}};
}

nlohmann::json to_json(const std::string& tlog, const telemetry::ImuWindow& window, const telemetry::ImuSeries& series,
                       const std::vector<telemetry::AxisSpectrum>& axes) {
  const telemetry::AmplitudeSpectrum& first = axes.front().spectrum;
  nlohmann::json j{{"file", tlog},
                   {"window", window_json(window)},
                   {"samples", series.samples},
                   {"rate_hz", series.rate_hz},
                   {"duration_s", series.duration_s},
                   {"max_samples", telemetry::kMaxImuSeriesSamples},
                   {"samples_beyond_cap", series.samples_beyond_cap},
                   {"other_systems", series.other_systems},
                   {"gaps", series.gaps},
                   {"window_function", "hann"},
                   {"overlap", 0.5},
                   {"segment_samples", first.segment_samples},
                   {"segments", first.segments},
                   {"resolution_hz", first.resolution_hz},
                   {"nyquist_hz", series.rate_hz / 2.0}};
  for (const telemetry::AxisSpectrum& a : axes) {
    nlohmann::json peaks = nlohmann::json::array();
    for (const telemetry::SpectrumPoint& p : a.spectrum.peaks) peaks.push_back({{"frequency_hz", p.frequency_hz}, {"amplitude", p.amplitude}});
    nlohmann::json curve = nlohmann::json::array();
    for (const telemetry::SpectrumPoint& p : telemetry::decimate_spectrum(a.spectrum.curve, kSpectrumJsonPoints))
      curve.push_back({p.frequency_hz, p.amplitude});
    j["sensors"][a.sensor]["unit"] = a.unit;
    j["sensors"][a.sensor]["axes"][a.axis] = {{"peaks", peaks}, {"curve", curve}};
  }
  return j;
}

void print_text(const std::string& tlog, const telemetry::ImuSeries& series, const std::vector<telemetry::AxisSpectrum>& axes) {
  const telemetry::AmplitudeSpectrum& first = axes.front().spectrum;
  std::cout << tlog << ": " << series.samples << " IMU samples (HIL_SENSOR) at " << number(series.rate_hz) << " Hz over "
            << number(series.duration_s) << " s; at most " << telemetry::kMaxImuSeriesSamples << " samples are read";
  if (series.samples_beyond_cap > 0) std::cout << " (" << series.samples_beyond_cap << " more not read)";
  std::cout << "\n";
  if (series.gaps > 0) std::cout << "warning: " << series.gaps << " gaps over 1.5 sample intervals: the spectrum assumes a steady rate\n";
  if (series.other_systems > 0) std::cout << "note: " << series.other_systems << " HIL_SENSOR from other systems left out\n";
  std::cout << "amplitude spectrum (Welch: " << first.segments << " Hann segments of " << first.segment_samples
            << " samples, 50 % overlap, " << number(first.resolution_hz) << " Hz resolution, up to "
            << number(series.rate_hz / 2.0) << " Hz); strongest peaks, frequency Hz amplitude:\n";
  for (const telemetry::AxisSpectrum& a : axes) {
    std::cout << a.sensor << " " << a.axis << " (" << a.unit << "):";
    for (const telemetry::SpectrumPoint& p : a.spectrum.peaks) std::cout << "  " << number(p.frequency_hz) << " " << number(p.amplitude);
    std::cout << "\n";
  }
  std::cout << std::flush;
}

}  // namespace

int run_inspect_spectrum(const GlobalOptions& global, const std::string& tlog, const telemetry::ImuWindow& window) {
  auto series = telemetry::read_imu_series(tlog, telemetry::kMaxImuSeriesSamples, window);
  if (!series) return log_error("inspect", series.error());
  const std::size_t segment = telemetry::spectrum_segment_samples(*series);
  if (series->samples < segment)
    return log_error("inspect", Error::input("'" + tlog + "' holds " + std::to_string(series->samples) +
                                                 " IMU samples" + (window.whole() ? "" : " in the --from/--to window") +
                                                 "; the spectrum needs at least one segment of " + std::to_string(segment) +
                                                 " (1 s at " + number(series->rate_hz) + " Hz)"));
  const auto axes = telemetry::imu_spectrum(*series);
  if (global.json) print_json_line(to_json(tlog, window, *series, axes));
  else print_text(tlog, *series, axes);
  return kExitOk;
}

}  // namespace hitl::cli
