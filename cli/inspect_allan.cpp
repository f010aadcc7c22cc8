#include "cli/inspect_allan.h"

#include <iostream>

#include <nlohmann/json.hpp>

#include "cli/imu_series_output.h"
#include "engine/telemetry/imu_series.h"

namespace hitl::cli {
namespace {

nlohmann::json to_json(const std::string& tlog, const telemetry::ImuSeries& series, const std::vector<telemetry::AxisAllan>& axes) {
  nlohmann::json j = imu_series_json(tlog, series);
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
  print_imu_series_header(tlog, series, "the curve");
  std::cout << "overlapping Allan deviation; noise_density: the tau = 1 s value of the -1/2 slope; "
               "bias_instability: the minimum / 0.664\n";
  for (const telemetry::AxisAllan& a : axes) {
    std::cout << a.sensor << " " << a.axis << ": noise_density " << imu_figure(a.fit.noise_density) << " " << a.unit
              << "/sqrt(Hz), bias_instability " << imu_figure(a.fit.bias_instability) << " " << a.unit << " (minimum at tau "
              << imu_figure(a.fit.minimum_tau_s) << " s)\n";
  }
  std::cout << "tau_s";
  for (const telemetry::AxisAllan& a : axes) std::cout << " " << a.sensor << "_" << a.axis;
  std::cout << "\n";
  for (std::size_t i = 0; i < axes.front().curve.size(); ++i) {
    std::cout << imu_figure(axes.front().curve[i].tau_s);
    for (const telemetry::AxisAllan& a : axes) std::cout << " " << imu_figure(a.curve[i].deviation);
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
