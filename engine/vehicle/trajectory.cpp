#include "base/common/bounded_read.h"
#include "base/common/json_nesting.h"
#include "engine/vehicle/trajectory.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <tuple>

namespace hitl::vehicle {

double wrap_pi(double a) {
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a <= 0) a += 2.0 * M_PI;
  return a - M_PI;
}

namespace {
constexpr double kMaxTime_s = 86400;         ///< one day
constexpr double kMaxHorizontal_m = 10000;  ///< x, y from home
constexpr double kMaxHeight_m = 1000;       ///< z above home
constexpr double kMaxYaw_rad = 100;         ///< unwrapped yaw (about 16 turns)

std::string compact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

Expected<Trajectory> Trajectory::parse(std::string_view text, std::string_view source) {
  const std::string src(source);
  if (auto depth = check_json_depth(text, src); !depth) return depth.error();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    return Error::input(src + ": not valid JSON (" + e.what() + ")");
  }
  if (!j.is_object() || !j.contains("waypoints") || !j["waypoints"].is_array())
    return Error::input(src + ": expected an object with a \"waypoints\" array");
  const auto& list = j["waypoints"];
  if (list.empty()) return Error::input(src + ": \"waypoints\" is empty");
  Trajectory tr;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = src + ": waypoints[" + std::to_string(i) + "]";
    const auto& w = list[i];
    if (!w.is_object()) return Error::input(where + ": expected an object {t, x, y, z, yaw}");
    for (const auto& [key, value] : w.items())
      if (key != "t" && key != "x" && key != "y" && key != "z" && key != "yaw")
        return Error::input(where + "." + key + ": unknown field (expected t, x, y, z, yaw)");
    Waypoint wp;
    auto number = [&](const char* key, double& out, bool required) -> Status {
      if (!w.contains(key)) {
        if (required) return Error::input(where + "." + key + ": missing");
        return Ok{};
      }
      if (!w[key].is_number()) return Error::input(where + "." + key + ": must be a number");
      out = w[key].get<double>();
      if (!std::isfinite(out)) return Error::input(where + "." + key + ": must be finite");
      return Ok{};
    };
    for (auto st : {number("t", wp.t_s, true), number("x", wp.p_ENU_m[0], true), number("y", wp.p_ENU_m[1], true),
                    number("z", wp.p_ENU_m[2], true), number("yaw", wp.yaw_ENU_rad, false)})
      if (!st) return st.error();
    if (wp.t_s < 0) return Error::input(where + ".t: must be >= 0 (got " + std::to_string(wp.t_s) + ")");
    // Physical limits: a flight of at most a day within 10 km of home and 1 km up.
    if (wp.t_s > kMaxTime_s)
      return Error::input(where + ".t: must be <= " + std::to_string(static_cast<int>(kMaxTime_s)) + " s (got " + compact(wp.t_s) + ")");
    const std::tuple<const char*, double, double, const char*> limits[] = {{"x", wp.p_ENU_m[0], kMaxHorizontal_m, "m"},
                                                                           {"y", wp.p_ENU_m[1], kMaxHorizontal_m, "m"},
                                                                           {"z", wp.p_ENU_m[2], kMaxHeight_m, "m"},
                                                                           {"yaw", wp.yaw_ENU_rad, kMaxYaw_rad, "rad"}};
    for (const auto& [key, value, limit, unit] : limits)
      if (std::abs(value) > limit)
        return Error::input(where + "." + key + ": must be within +-" + std::to_string(static_cast<int>(limit)) + " " + unit +
                     " (got " + compact(value) + ")");
    if (!tr.waypoints_.empty() && wp.t_s <= tr.waypoints_.back().t_s)
      return Error::input(where + ".t: times must increase (" + std::to_string(wp.t_s) + " after " +
                   std::to_string(tr.waypoints_.back().t_s) + ")");
    if (wp.p_ENU_m[2] < 0) return Error::input(where + ".z: must be >= 0 m above home (got " + std::to_string(wp.p_ENU_m[2]) + ")");
    tr.waypoints_.push_back(wp);
  }
  return tr;
}

Expected<Trajectory> Trajectory::load(const std::string& path) {
  auto text = read_bounded_file(path, "trajectory", kMaxTrajectoryFileBytes);
  if (!text) return text.error();
  return parse(*text, path);
}

TrajectoryReference Trajectory::at(double t_s) const {
  TrajectoryReference r;
  const auto& w = waypoints_;
  if (t_s <= w.front().t_s || w.size() == 1) {
    r.p_ENU_m = w.front().p_ENU_m;
    r.yaw_ENU_rad = w.front().yaw_ENU_rad;
    return r;
  }
  if (t_s >= w.back().t_s) {
    r.p_ENU_m = w.back().p_ENU_m;
    r.yaw_ENU_rad = wrap_pi(w.back().yaw_ENU_rad);
    return r;
  }
  std::size_t i = 1;
  while (w[i].t_s < t_s) ++i;
  const Waypoint& a = w[i - 1];
  const Waypoint& b = w[i];
  const double span = b.t_s - a.t_s;
  const double f = (t_s - a.t_s) / span;
  for (int k = 0; k < 3; ++k) {
    r.p_ENU_m[static_cast<std::size_t>(k)] = a.p_ENU_m[static_cast<std::size_t>(k)] +
                                             f * (b.p_ENU_m[static_cast<std::size_t>(k)] - a.p_ENU_m[static_cast<std::size_t>(k)]);
    r.v_ENU_m_s[static_cast<std::size_t>(k)] = (b.p_ENU_m[static_cast<std::size_t>(k)] - a.p_ENU_m[static_cast<std::size_t>(k)]) / span;
  }
  r.yaw_ENU_rad = wrap_pi(a.yaw_ENU_rad + f * wrap_pi(b.yaw_ENU_rad - a.yaw_ENU_rad));
  return r;
}

}  // namespace hitl::vehicle
