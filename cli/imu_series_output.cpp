#include "cli/imu_series_output.h"

#include <cstdio>
#include <iostream>

namespace hitl::cli {

std::string imu_figure(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

nlohmann::json imu_series_json(const std::string& tlog, const telemetry::ImuSeries& series) {
  return {{"file", tlog},
          {"samples", series.samples},
          {"rate_hz", series.rate_hz},
          {"duration_s", series.duration_s},
          {"max_samples", telemetry::kMaxImuSeriesSamples},
          {"samples_beyond_cap", series.samples_beyond_cap},
          {"other_systems", series.other_systems},
          {"gaps", series.gaps}};
}

void print_imu_series_header(const std::string& tlog, const telemetry::ImuSeries& series, const char* what) {
  std::cout << tlog << ": " << series.samples << " IMU samples (HIL_SENSOR) at " << imu_figure(series.rate_hz) << " Hz over "
            << imu_figure(series.duration_s) << " s; at most " << telemetry::kMaxImuSeriesSamples << " samples are read";
  if (series.samples_beyond_cap > 0) std::cout << " (" << series.samples_beyond_cap << " more not read)";
  std::cout << "\n";
  if (series.gaps > 0) std::cout << "warning: " << series.gaps << " gaps over 1.5 sample intervals: " << what << " assumes a steady rate\n";
  if (series.other_systems > 0) std::cout << "note: " << series.other_systems << " HIL_SENSOR from other systems left out\n";
}

}  // namespace hitl::cli
