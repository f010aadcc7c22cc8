// A trajectory file as the spec's trajectory_rc plugin reads it: timestamped waypoints in ENU
// metres (relative to home) and yaw in radians (ENU: 0 = east, counter-clockwise positive),
//   {"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2.0, "yaw": 0}, ...]}
// interpolated linearly between waypoints, yaw the short way round.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"

namespace hitl::vehicle {

struct Waypoint {
  double t_s = 0;
  std::array<double, 3> p_ENU_m{};
  double yaw_ENU_rad = 0;
};

struct TrajectoryReference {
  std::array<double, 3> p_ENU_m{};
  std::array<double, 3> v_ENU_m_s{};  ///< of the segment (feed-forward)
  double yaw_ENU_rad = 0;
};

class Trajectory {
 public:
  /// Parses and checks a file's text; errors name the source, the waypoint and the field.
  static Expected<Trajectory> parse(std::string_view json_text, std::string_view source);
  static Expected<Trajectory> load(const std::string& path);

  const std::vector<Waypoint>& waypoints() const { return waypoints_; }
  double duration_s() const { return waypoints_.back().t_s; }
  /// The reference at time t (clamped to the first and last waypoint).
  TrajectoryReference at(double t_s) const;

 private:
  std::vector<Waypoint> waypoints_;
};

/// Wraps an angle to (-pi, pi].
double wrap_pi(double angle_rad);

}  // namespace hitl::vehicle
