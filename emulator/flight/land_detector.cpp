#include "emulator/flight/land_detector.h"

#include <cmath>
#include <numbers>

namespace hitl::flight {

void LandDetector::reset() {
  contact_time_s_ = maybe_landed_time_s_ = 0.0;
  ground_contact_ = landed_ = false;
}

bool LandDetector::update(const LandDetectorInput& in, const FlightParams& params, double dt_s) {
  constexpr double kContactTime_s = 0.35;
  constexpr double kMaxRotation_rad_s = 20.0 * std::numbers::pi / 180.0;
  const bool descending = in.v_sp_NED_m_s.z() > 0.1;
  const bool still_vertical = std::abs(in.v_NED_m_s.z()) < 0.5 * params.LNDMC_Z_VEL_MAX;
  const bool still_horizontal = in.v_NED_m_s.head<2>().norm() < params.LNDMC_XY_VEL_MAX;
  contact_time_s_ = (descending && still_vertical && still_horizontal) ? contact_time_s_ + dt_s : 0.0;
  ground_contact_ = contact_time_s_ >= kContactTime_s;

  const double low_thrust = params.MPC_THR_MIN + 0.3 * (params.MPC_THR_HOVER - params.MPC_THR_MIN);
  const bool maybe_landed =
      ground_contact_ && in.collective_thrust <= low_thrust && in.w_FRD_rad_s.norm() < kMaxRotation_rad_s;
  maybe_landed_time_s_ = maybe_landed ? maybe_landed_time_s_ + dt_s : 0.0;
  landed_ = maybe_landed_time_s_ >= params.LNDMC_TRIG_TIME;
  return landed_;
}

}  // namespace hitl::flight
