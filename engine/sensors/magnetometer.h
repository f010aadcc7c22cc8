// Magnetometer: Earth's field at home (declination D, inclination I, strength F),
//   B_NED = F (cos I cos D, cos I sin D, sin I),   mag_FRD = R_FRD_to_NED^T B_NED + noise  [gauss]
// then rounded to the part's LSB and held within its full scale (resolution_gauss, range_gauss; 0: none).
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/inertial_noise.h"
#include "engine/sensors/samples.h"

namespace hitl::sensors {

Eigen::Vector3d earth_field_NED_gauss(const model::MagneticFieldConfig& field);

class Magnetometer {
 public:
  Magnetometer(const model::MagConfig& config, const model::MagneticFieldConfig& field, std::uint64_t seed);
  MagSample sample(const model::VehicleState& state, double t_s);
  void reset();
  double rate_hz() const { return config_.rate_hz; }
  const InertialNoise& noise() const { return noise_; }

 private:
  model::MagConfig config_;
  Eigen::Vector3d field_NED_gauss_;
  InertialNoise noise_;
  double last_t_s_ = -1.0;
};

}  // namespace hitl::sensors
