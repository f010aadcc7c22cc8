#include "engine/sensors/geodesy.h"

#include <GeographicLib/LocalCartesian.hpp>

namespace hitl::sensors {

LocalGeodesy::LocalGeodesy(const model::HomeConfig& home)
    : local_(std::make_unique<GeographicLib::LocalCartesian>(home.lat_deg, home.lon_deg, home.alt_m)) {}

LocalGeodesy::~LocalGeodesy() = default;

Geodetic LocalGeodesy::to_geodetic(const Eigen::Vector3d& p_ENU_m) const {
  Geodetic g;
  local_->Reverse(p_ENU_m.x(), p_ENU_m.y(), p_ENU_m.z(), g.lat_deg, g.lon_deg, g.alt_m);
  return g;
}

Eigen::Vector3d LocalGeodesy::to_local_ENU_m(const Geodetic& g) const {
  Eigen::Vector3d p;
  local_->Forward(g.lat_deg, g.lon_deg, g.alt_m, p.x(), p.y(), p.z());
  return p;
}

}  // namespace hitl::sensors
