// What `hitl inspect --tlog FILE --allan` and `--spectrum` both say of the IMU series they read
// (engine/telemetry/imu_series.h): its figures in the JSON object, and the text's opening lines.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "engine/telemetry/imu_series.h"

namespace hitl::cli {

/// "%.4g": the figures of both outputs.
std::string imu_figure(double v);
/// file, samples, rate_hz, duration_s, max_samples, samples_beyond_cap, other_systems, gaps.
nlohmann::json imu_series_json(const std::string& tlog, const telemetry::ImuSeries& series);
/// The series in one line, then a warning for gaps (`what` assumes a steady rate: "the curve",
/// "the spectrum") and a note for other systems' HIL_SENSOR left out.
void print_imu_series_header(const std::string& tlog, const telemetry::ImuSeries& series, const char* what);

}  // namespace hitl::cli
