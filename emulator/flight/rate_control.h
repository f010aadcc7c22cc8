// PX4's multicopter rate controller (mc_rate_control RateControl), body FRD, normalized torque:
//   torque = P (rate_sp - rate) + integral - D angular_accel
//   integral += I (rate_sp - rate) dt max(0, 1 - (error / 400 deg/s)^2), clamped to MC_*_INT_LIM;
//   frozen while landed and on the saturated side of a saturated axis.
#pragma once

#include <array>

#include <Eigen/Core>

#include "emulator/flight/flight_params.h"

namespace hitl::flight {

class RateControl {
 public:
  void reset() { integral_.setZero(); }
  /// saturated_positive/negative: per axis, the mixer could not deliver more/less torque last step.
  Eigen::Vector3d update(const Eigen::Vector3d& rate_sp_FRD_rad_s, const Eigen::Vector3d& rate_FRD_rad_s,
                         const Eigen::Vector3d& angular_accel_FRD_rad_s2, double dt_s, bool landed,
                         const FlightParams& params, const std::array<bool, 3>& saturated_positive = {},
                         const std::array<bool, 3>& saturated_negative = {});
  const Eigen::Vector3d& integral() const { return integral_; }

 private:
  Eigen::Vector3d integral_ = Eigen::Vector3d::Zero();
};

}  // namespace hitl::flight
