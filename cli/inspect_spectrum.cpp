#include "cli/inspect_spectrum.h"

#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli/imu_series_output.h"
#include "engine/telemetry/imu_spectrum.h"

namespace hitl::cli {
namespace {

nlohmann::json window_json(const telemetry::ImuWindow& window) {
  return {{"from_s", window.from_s}, {"to_s", std::isfinite(window.to_s) ? nlohmann::json(window.to_s) : nlohmann::json(nullptr)}};
}

nlohmann::json to_json(const std::string& tlog, const telemetry::ImuWindow& window, const telemetry::ImuSeries& series,
                       const std::vector<telemetry::AxisSpectrum>& axes) {
  const telemetry::AmplitudeSpectrum& first = axes.front().spectrum;
  nlohmann::json j = imu_series_json(tlog, series);
  j["window"] = window_json(window);
  j["window_function"] = "hann";
  j["overlap"] = 0.5;
  j["segment_samples"] = first.segment_samples;
  j["segments"] = first.segments;
  j["resolution_hz"] = first.resolution_hz;
  j["nyquist_hz"] = series.rate_hz / 2.0;
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
  print_imu_series_header(tlog, series, "the spectrum");
  std::cout << "amplitude spectrum (Welch: " << first.segments << " Hann segments of " << first.segment_samples
            << " samples, 50 % overlap, " << imu_figure(first.resolution_hz) << " Hz resolution, up to "
            << imu_figure(series.rate_hz / 2.0) << " Hz); strongest peaks, frequency Hz amplitude:\n";
  for (const telemetry::AxisSpectrum& a : axes) {
    std::cout << a.sensor << " " << a.axis << " (" << a.unit << "):";
    for (const telemetry::SpectrumPoint& p : a.spectrum.peaks) std::cout << "  " << imu_figure(p.frequency_hz) << " " << imu_figure(p.amplitude);
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
                                                 " (1 s at " + imu_figure(series->rate_hz) + " Hz)"));
  const auto axes = telemetry::imu_spectrum(*series);
  if (global.json) print_json_line(to_json(tlog, window, *series, axes));
  else print_text(tlog, *series, axes);
  return kExitOk;
}

}  // namespace hitl::cli
