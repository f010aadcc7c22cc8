#include "engine/report/px4_estimate.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string_view>

#include "engine/frames/frames.h"
#include "engine/ulog/ulog.h"

namespace hitl::report {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kMaxShift_s = 0.5;
constexpr double kShiftStep_s = 0.004;  ///< one simulator step
constexpr double kMinHeightChange_m = 0.5;  ///< a flight that climbed less has no lag to fit

/// The truth's (north, east, down) at `t_s`, linear between its samples; nullopt outside them.
std::optional<std::array<double, 3>> truth_at(const Track& truth, double t_s) {
  if (truth.size() == 0 || t_s < truth.t_s.front() || t_s > truth.t_s.back()) return std::nullopt;
  const auto it = std::lower_bound(truth.t_s.begin(), truth.t_s.end(), t_s);
  const std::size_t i = static_cast<std::size_t>(it - truth.t_s.begin());
  if (i == 0 || truth.t_s[i] == t_s) return std::array<double, 3>{truth.north_m[i], truth.east_m[i], truth.down_m[i]};
  const double f = (t_s - truth.t_s[i - 1]) / (truth.t_s[i] - truth.t_s[i - 1]);
  auto lerp = [&](const std::vector<double>& v) { return v[i - 1] + f * (v[i] - v[i - 1]); };
  return std::array<double, 3>{lerp(truth.north_m), lerp(truth.east_m), lerp(truth.down_m)};
}

constexpr std::size_t kMaxShiftSamples = 2000;  ///< PX4's samples the shift is fitted on (evenly)

/// The standard deviation of PX4's down minus the truth's at t + shift, over the compared samples.
std::optional<double> spread_at_shift(const Track& px4, const Track& truth, double shift_s) {
  double sum = 0, sum_sq = 0;
  std::size_t n = 0;
  const std::size_t stride = std::max<std::size_t>(1, px4.size() / kMaxShiftSamples);
  for (std::size_t i = 0; i < px4.size(); i += stride) {
    const auto t = truth_at(truth, px4.t_s[i] + shift_s);
    if (!t) continue;
    const double d = px4.down_m[i] - (*t)[2];
    sum += d, sum_sq += d * d, ++n;
  }
  if (n < 10) return std::nullopt;
  const double mean = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, sum_sq / static_cast<double>(n) - mean * mean));
}

std::string version_of(const ulog::ULogFile& u) {
  const auto it = u.info.find("ver_sw_release");
  if (it == u.info.end()) return "";
  const auto v = static_cast<uint32_t>(std::strtoull(it->second.c_str(), nullptr, 10));
  return "v" + std::to_string(v >> 24) + "." + std::to_string((v >> 16) & 0xff) + "." + std::to_string((v >> 8) & 0xff);
}

}  // namespace

std::optional<std::string> find_px4_ulog(const std::string& tlog_path) {
  std::filesystem::path stem(tlog_path);
  if (stem.extension() == ".tlog") stem.replace_extension();
  const std::filesystem::path logs = stem.string() + ".px4/log";
  std::error_code ec;
  if (!std::filesystem::is_directory(logs, ec)) return std::nullopt;
  std::optional<std::string> newest;
  std::filesystem::file_time_type newest_time{};
  std::size_t seen = 0;
  for (auto it = std::filesystem::recursive_directory_iterator(logs, ec); !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec)) {
    if (++seen > 10000 || it.depth() > 2) break;  // PX4 writes log/<date>/<time>.ulg: two levels
    if (!it->is_regular_file(ec) || it->path().extension() != ".ulg") continue;
    const auto t = it->last_write_time(ec);
    if (ec) continue;
    if (!newest || t > newest_time) newest = it->path().string(), newest_time = t;
  }
  return newest;
}

Expected<Px4Estimate> read_px4_estimate(const std::string& ulog_path, const FlightLog& log) {
  if (!log.simulated_time)
    return Error::input("PX4's ULog '" + ulog_path + "' cannot be placed on this recording's time: it has no simulator's clock "
                        "(HIL_SENSOR from a simulator)");
  std::vector<ulog::Request> requests = {{"vehicle_local_position", {"x", "y", "z", "xy_valid", "z_valid"}, 0},
                                         {"vehicle_attitude", {"q[0]", "q[1]", "q[2]", "q[3]"}, 0},
                                         {"vehicle_rates_setpoint", {"roll", "pitch", "yaw"}, 0},
                                         {"vehicle_angular_velocity", {"xyz[0]", "xyz[1]", "xyz[2]"}, 0}};
  // EKF2's innovations and test ratios, one request a field: a PX4 without one of them keeps the rest.
  const std::size_t innovations_at = requests.size();
  for (const auto& f : kPx4InnovationFields) requests.push_back({"estimator_innovations", {f.field}, 0});
  const std::size_t ratios_at = requests.size();
  for (const auto& f : kPx4TestRatioFields) requests.push_back({"estimator_innovation_test_ratios", {f.field}, 0});
  auto u = ulog::read_ulog(ulog_path, requests);
  if (!u) return u.error();
  Px4Estimate px4;
  px4.path = ulog_path;
  px4.version = version_of(*u);
  px4.notes = u->notes;
  px4.parameters = u->parameters;
  for (const auto& [name, d] : u->parameter_defaults)
    if (d.current_setup || d.system) px4.parameter_defaults[name] = d.current_setup ? *d.current_setup : *d.system;
  const auto& pos = u->series[0];
  const auto& att = u->series[1];
  if (!pos.missing.empty()) px4.notes.push_back("vehicle_local_position: " + pos.missing);
  if (!att.missing.empty()) px4.notes.push_back("vehicle_attitude: " + att.missing);
  // In lockstep PX4's clock is the simulator's: a ULog timestamp is the HIL_SENSOR time_usec.
  const double first_s = log.start_s, last_s = log.start_s + log.duration_s;
  std::size_t outside = 0;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const double t_s = static_cast<double>(pos.timestamp_us[i]) * 1e-6;
    if (t_s < first_s || t_s > last_s) {
      ++outside;
      continue;
    }
    if (pos.values[3][i] == 0 || pos.values[4][i] == 0) continue;  // not valid yet: PX4 says so itself
    px4.position.t_s.push_back(t_s);
    px4.position.north_m.push_back(pos.values[0][i]);
    px4.position.east_m.push_back(pos.values[1][i]);
    px4.position.down_m.push_back(pos.values[2][i]);
  }
  for (std::size_t i = 0; i < att.size(); ++i) {
    const double t_s = static_cast<double>(att.timestamp_us[i]) * 1e-6;
    if (t_s < first_s || t_s > last_s) continue;
    const Eigen::Quaterniond q(att.values[0][i], att.values[1][i], att.values[2][i], att.values[3][i]);
    if (!q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 0.01) continue;
    const auto e = frames::euler_from(q);
    px4.attitude.t_s.push_back(t_s);
    px4.attitude.roll_deg.push_back(e.roll_rad * kRadToDeg);
    px4.attitude.pitch_deg.push_back(e.pitch_rad * kRadToDeg);
    px4.attitude.yaw_deg.push_back(e.yaw_rad * kRadToDeg);
  }
  // The rate controller's input and what it saw, when PX4 logged them (its default logging does;
  // their absence is no note: the rate plots say what they draw).
  for (const auto& [series, track] : {std::pair{&u->series[2], &px4.rate_setpoint}, std::pair{&u->series[3], &px4.rates}}) {
    if (!series->missing.empty()) continue;
    for (std::size_t i = 0; i < series->size(); ++i) {
      const double t_s = static_cast<double>(series->timestamp_us[i]) * 1e-6;
      if (t_s < first_s || t_s > last_s) continue;
      track->t_s.push_back(t_s);
      track->roll_deg_s.push_back(series->values[0][i] * kRadToDeg);
      track->pitch_deg_s.push_back(series->values[1][i] * kRadToDeg);
      track->yaw_deg_s.push_back(series->values[2][i] * kRadToDeg);
    }
  }
  // EKF2's innovations and test ratios on the same clock; a field 0 throughout is a source not fused.
  auto innovations = [&](std::size_t at, const auto& fields, std::vector<Px4Innovation>& out) {
    std::size_t k = at;
    for (const auto& f : fields) {
      const auto& series = u->series[k++];
      if (!series.missing.empty()) {
        if (px4.innovations_missing.empty()) px4.innovations_missing = series.request.topic + ": " + series.missing;
        continue;
      }
      Px4Innovation innovation{f.field, f.name, f.group, {}};
      const double scale = std::string_view(f.unit) == "deg" ? kRadToDeg : 1.0;
      bool nonzero = false;
      for (std::size_t i = 0; i < series.size(); ++i) {
        const double t_s = static_cast<double>(series.timestamp_us[i]) * 1e-6;
        const double v = series.values[0][i] * scale;
        if (t_s < first_s || t_s > last_s || !std::isfinite(v)) continue;
        nonzero = nonzero || v != 0;
        innovation.value.t_s.push_back(t_s);
        innovation.value.value.push_back(v);
      }
      if (nonzero) out.push_back(std::move(innovation));
      else if (series.size() > 0 && &out == &px4.innovations) px4.innovations_zero.push_back(f.name);
    }
  };
  innovations(innovations_at, kPx4InnovationFields, px4.innovations);
  innovations(ratios_at, kPx4TestRatioFields, px4.test_ratios);
  if (pos.size() > 0 && outside == pos.size())
    return Error::input("PX4's ULog '" + ulog_path + "' is of another time: its vehicle_local_position runs from " +
                        std::to_string(static_cast<double>(pos.timestamp_us.front()) * 1e-6) + " to " +
                        std::to_string(static_cast<double>(pos.timestamp_us.back()) * 1e-6) + " s, the recording from " +
                        std::to_string(first_s) + " to " + std::to_string(last_s) +
                        " s of the simulator's clock (another session's log, or PX4 not in lockstep)");
  if (outside > 0)
    px4.notes.push_back(std::to_string(outside) + " vehicle_local_position samples outside the recording's time (not drawn)");
  // PX4's estimate minus the truth, where both are.
  double sum_sq = 0;
  for (std::size_t i = 0; i < px4.position.size(); ++i) {
    const auto t = truth_at(log.truth, px4.position.t_s[i]);
    if (!t) continue;
    const std::array<double, 3> d = {px4.position.north_m[i] - (*t)[0], px4.position.east_m[i] - (*t)[1],
                                     px4.position.down_m[i] - (*t)[2]};
    px4.minus_truth.t_s.push_back(px4.position.t_s[i]);
    px4.minus_truth.north_m.push_back(d[0]);
    px4.minus_truth.east_m.push_back(d[1]);
    px4.minus_truth.down_m.push_back(d[2]);
    for (std::size_t k = 0; k < 3; ++k) px4.mean_offset_NED_m[k] += d[k];
    sum_sq += d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  }
  const std::size_t n = px4.minus_truth.size();
  if (n > 0) {
    for (double& m : px4.mean_offset_NED_m) m /= static_cast<double>(n);
    px4.rms_m = std::sqrt(sum_sq / static_cast<double>(n));
  } else if (log.truth.size() == 0) {
    px4.notes.push_back("no truth in the recording to compare PX4's estimate with");
  }
  // The lag: PX4's height at t against the truth's at t + shift; the best shift is minus the lag.
  std::optional<double> best_spread;
  // Only a flight that climbed or descended has a lag to fit: at rest every shift fits alike.
  double low_m = 0, high_m = 0;
  for (std::size_t i = 0; i < log.truth.size(); ++i) {
    if (i == 0 || log.truth.down_m[i] < low_m) low_m = log.truth.down_m[i];
    if (i == 0 || log.truth.down_m[i] > high_m) high_m = log.truth.down_m[i];
  }
  if (high_m - low_m < kMinHeightChange_m) {
    px4.notes.push_back("no lag fitted: the truth's height changed less than " + std::to_string(kMinHeightChange_m).substr(0, 3) +
                        " m (nothing to fit it on)");
    return px4;
  }
  const int steps = static_cast<int>(std::lround(kMaxShift_s / kShiftStep_s));
  for (int k = -steps; k <= steps; ++k) {
    const double shift_s = k * kShiftStep_s;
    const auto spread = spread_at_shift(px4.position, log.truth, shift_s);
    if (spread && (!best_spread || *spread < *best_spread)) best_spread = spread, px4.lag_s = -shift_s;
  }
  if (px4.lag_s && std::abs(*px4.lag_s) >= kMaxShift_s - 1e-9) {
    px4.notes.push_back("no lag fitted: none within 0.5 s fits PX4's heights to the truth's");
    px4.lag_s.reset();
  }
  return px4;
}

}  // namespace hitl::report
