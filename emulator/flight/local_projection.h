// Local tangent plane around a reference point: PX4's azimuthal equidistant map projection
// (lib/geo) on a sphere of radius 6371 km, and the ISA altitude of a pressure (x500.md):
//   p = 101325 (1 - 2.25577e-5 h)^5.25588  <=>  h = (1 - (p / 101325)^(1 / 5.25588)) / 2.25577e-5
#pragma once

#include <Eigen/Core>

namespace hitl::flight {

inline constexpr double kEarthRadius_m = 6371000.0;
inline constexpr double kGravity_m_s2 = 9.80665;

struct LatLon {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
};

class LocalProjection {
 public:
  LocalProjection() = default;
  LocalProjection(double lat0_deg, double lon0_deg);
  bool valid() const { return valid_; }
  LatLon origin() const { return {lat0_deg_, lon0_deg_}; }
  /// North/east metres of a point from the origin.
  Eigen::Vector2d to_NE_m(double lat_deg, double lon_deg) const;
  LatLon to_lat_lon(const Eigen::Vector2d& p_NE_m) const;

 private:
  bool valid_ = false;
  double lat0_deg_ = 0.0, lon0_deg_ = 0.0;
  double sin_lat0_ = 0.0, cos_lat0_ = 1.0;
};

/// ISA (troposphere) pressure altitude [m] of an absolute pressure [Pa].
double isa_altitude_m(double pressure_Pa);

}  // namespace hitl::flight
