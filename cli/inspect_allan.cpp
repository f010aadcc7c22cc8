#include "cli/inspect_allan.h"

#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "engine/telemetry/imu_series.h"

namespace hitl::cli {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

nlohmann::json to_json(const std::string& tlog, const telemetry::ImuSeries& series, const std::vector<telemetry::AxisAllan>& axes) {
  nlohmann::json j{{"file", tlog},
                   {"samples", series.samples},
                   {"rate_hz", series.rate_hz},
                   {"duration_s", series.duration_s},
                   {"max_samples", telemetry::kMaxImuSeriesSamples},
                   {"samples_beyond_cap", series.samples_beyond_cap},
                   {"other_systems", series.other_systems},
                   {"gaps", series.gaps}};
  for (const telemetry::AxisAllan& a : axes) {
    nlohmann::json curve = nlohmann::json::array();
    for (const telemetry::AllanPoint& p : a.curve) curve.push_back({p.tau_s, p.deviation});
    j["sensors"][a.sensor]["unit"] = a.unit;
    j["sensors"][a.sensor]["axes"][a.axis] = {{"noise_density", a.fit.noise_density},
                                              {"bias_instability", a.fit.bias_instability},
                                              {"minimum_tau_s", a.fit.minimum_tau_s},
                                              {"fit_points", a.fit.fit_points},
                                              {"curve", curve}};
  }
  return j;
}

void print_text(const std::string& tlog, const telemetry::ImuSeries& series, const std::vector<telemetry::AxisAllan>& axes) {
  std::cout << tlog << ": " << series.samples << " IMU samples (HIL_SENSOR) at " << number(series.rate_hz) << " Hz over "
            << number(series.duration_s) << " s; at most " << telemetry::kMaxImuSeriesSamples << " samples are read";
  if (series.samples_beyond_cap > 0) std::cout << " (" << series.samples_beyond_cap << " more not read)";
  std::cout << "\n";
  if (series.gaps > 0) std::cout << "warning: " << series.gaps << " gaps over 1.5 sample intervals: the curve assumes a steady rate\n";
  if (series.other_systems > 0)
    std::cout << "note: " << series.other_systems << " HIL_SENSOR from other systems left out\n";
  std::cout << "overlapping Allan deviation; noise_density: the tau = 1 s value of the -1/2 slope; "
               "bias_instability: the minimum / 0.664\n";
  for (const telemetry::AxisAllan& a : axes) {
    std::cout << a.sensor << " " << a.axis << ": noise_density " << number(a.fit.noise_density) << " " << a.unit
              << "/sqrt(Hz), bias_instability " << number(a.fit.bias_instability) << " " << a.unit << " (minimum at tau "
              << number(a.fit.minimum_tau_s) << " s)\n";
  }
  std::cout << "tau_s";
  for (const telemetry::AxisAllan& a : axes) std::cout << " " << a.sensor << "_" << a.axis;
  std::cout << "\n";
  for (std::size_t i = 0; i < axes.front().curve.size(); ++i) {
    std::cout << number(axes.front().curve[i].tau_s);
    for (const telemetry::AxisAllan& a : axes) std::cout << " " << number(a.curve[i].deviation);
    std::cout << "\n";
  }
  std::cout << std::flush;
}

}  // namespace

int run_inspect_allan(const GlobalOptions& global, const std::string& tlog, const telemetry::ImuWindow& window) {
  auto series = telemetry::read_imu_series(tlog, telemetry::kMaxImuSeriesSamples, window);
  if (!series) return log_error("inspect", series.error());
  const auto axes = telemetry::imu_allan(*series);
  if (global.json) print_json_line(to_json(tlog, *series, axes));
  else print_text(tlog, *series, axes);
  return kExitOk;
}

}  // namespace hitl::cli
