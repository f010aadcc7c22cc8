// Touchdown detection like PX4's MulticopterLandDetector, in two stages:
//   ground contact: descent commanded (v_sp_z > 0.1 m/s) but |v_z| < LNDMC_Z_VEL_MAX / 2 and
//                   |v_xy| < LNDMC_XY_VEL_MAX, for 0.35 s  (the position controller then ramps the
//                   thrust limit down)
//   landed:         ground contact and collective thrust <= MPC_THR_MIN + 0.3 (MPC_THR_HOVER -
//                   MPC_THR_MIN) and |body rate| < 20 deg/s, for LNDMC_TRIG_TIME
#pragma once

#include <Eigen/Core>

#include "emulator/flight/flight_params.h"

namespace hitl::flight {

struct LandDetectorInput {
  Eigen::Vector3d v_NED_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_sp_NED_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_FRD_rad_s = Eigen::Vector3d::Zero();
  double collective_thrust = 0.0;
};

class LandDetector {
 public:
  void reset();
  /// Returns true once landed.
  bool update(const LandDetectorInput& in, const FlightParams& params, double dt_s);
  bool ground_contact() const { return ground_contact_; }
  bool landed() const { return landed_; }

 private:
  double contact_time_s_ = 0.0;
  double maybe_landed_time_s_ = 0.0;
  bool ground_contact_ = false;
  bool landed_ = false;
};

}  // namespace hitl::flight
