#include "emulator/flight/local_projection.h"

#include "emulator/flight/flight_params.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hitl::flight {
LocalProjection::LocalProjection(double lat0_deg, double lon0_deg)
    : valid_(true), lat0_deg_(lat0_deg), lon0_deg_(lon0_deg),
      sin_lat0_(std::sin(lat0_deg * kDegToRad)), cos_lat0_(std::cos(lat0_deg * kDegToRad)) {}

Eigen::Vector2d LocalProjection::to_NE_m(double lat_deg, double lon_deg) const {
  const double lat_rad = lat_deg * kDegToRad;
  const double sin_lat = std::sin(lat_rad), cos_lat = std::cos(lat_rad);
  const double cos_dlon = std::cos((lon_deg - lon0_deg_) * kDegToRad);
  const double sin_dlon = std::sin((lon_deg - lon0_deg_) * kDegToRad);
  const double cos_c = std::clamp(sin_lat0_ * sin_lat + cos_lat0_ * cos_lat * cos_dlon, -1.0, 1.0);
  const double c = std::acos(cos_c);
  const double k = (std::abs(c) > 1e-12) ? c / std::sin(c) : 1.0;
  return {k * (cos_lat0_ * sin_lat - sin_lat0_ * cos_lat * cos_dlon) * kEarthRadius_m,
          k * cos_lat * sin_dlon * kEarthRadius_m};
}

LatLon LocalProjection::to_lat_lon(const Eigen::Vector2d& p_NE_m) const {
  const double x_rad = p_NE_m.x() / kEarthRadius_m;
  const double y_rad = p_NE_m.y() / kEarthRadius_m;
  const double c = std::hypot(x_rad, y_rad);
  if (c < 1e-15) return {lat0_deg_, lon0_deg_};
  const double sin_c = std::sin(c), cos_c = std::cos(c);
  const double lat_rad = std::asin(cos_c * sin_lat0_ + x_rad * sin_c * cos_lat0_ / c);
  const double dlon_rad = std::atan2(y_rad * sin_c, c * cos_lat0_ * cos_c - x_rad * sin_lat0_ * sin_c);
  return {lat_rad / kDegToRad, lon0_deg_ + dlon_rad / kDegToRad};
}

double isa_altitude_m(double pressure_Pa) {
  return (1.0 - std::pow(pressure_Pa / 101325.0, 1.0 / 5.25588)) / 2.25577e-5;
}

}  // namespace hitl::flight
