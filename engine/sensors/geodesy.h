// Local ENU position <-> WGS-84 geodetic coordinates around home (GeographicLib LocalCartesian:
// exact ellipsoidal conversion, not a flat-Earth approximation).
#pragma once

#include <memory>

#include <Eigen/Core>

#include "engine/model/world_config.h"

namespace GeographicLib {
class LocalCartesian;
}

namespace hitl::sensors {

struct Geodetic {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;
};

class LocalGeodesy {
 public:
  explicit LocalGeodesy(const model::HomeConfig& home);
  ~LocalGeodesy();
  LocalGeodesy(const LocalGeodesy&) = delete;
  LocalGeodesy& operator=(const LocalGeodesy&) = delete;

  /// A point at p_ENU_m from home (ENU origin at home, z up) in geodetic coordinates.
  Geodetic to_geodetic(const Eigen::Vector3d& p_ENU_m) const;
  Eigen::Vector3d to_local_ENU_m(const Geodetic& g) const;

 private:
  std::unique_ptr<GeographicLib::LocalCartesian> local_;
};

}  // namespace hitl::sensors
