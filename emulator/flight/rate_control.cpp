#include "emulator/flight/rate_control.h"

#include <algorithm>
#include <numbers>

namespace hitl::flight {

Eigen::Vector3d RateControl::update(const Eigen::Vector3d& rate_sp_FRD_rad_s, const Eigen::Vector3d& rate_FRD_rad_s,
                                    const Eigen::Vector3d& angular_accel_FRD_rad_s2, double dt_s, bool landed,
                                    const FlightParams& params, const std::array<bool, 3>& saturated_positive,
                                    const std::array<bool, 3>& saturated_negative) {
  const Eigen::Vector3d P(params.MC_ROLLRATE_P, params.MC_PITCHRATE_P, params.MC_YAWRATE_P);
  const Eigen::Vector3d I(params.MC_ROLLRATE_I, params.MC_PITCHRATE_I, params.MC_YAWRATE_I);
  const Eigen::Vector3d D(params.MC_ROLLRATE_D, params.MC_PITCHRATE_D, params.MC_YAWRATE_D);
  const Eigen::Vector3d limit(params.MC_RR_INT_LIM, params.MC_PR_INT_LIM, params.MC_YR_INT_LIM);
  const Eigen::Vector3d error = rate_sp_FRD_rad_s - rate_FRD_rad_s;
  const Eigen::Vector3d torque = P.cwiseProduct(error) + integral_ - D.cwiseProduct(angular_accel_FRD_rad_s2);
  if (!landed) {
    constexpr double kErrorScale_rad_s = 400.0 * std::numbers::pi / 180.0;
    for (int i = 0; i < 3; ++i) {
      double e = error[i];
      if ((saturated_positive[static_cast<std::size_t>(i)] && e > 0.0) ||
          (saturated_negative[static_cast<std::size_t>(i)] && e < 0.0)) {
        e = 0.0;
      }
      const double factor = std::max(0.0, 1.0 - (e / kErrorScale_rad_s) * (e / kErrorScale_rad_s));
      integral_[i] = std::clamp(integral_[i] + factor * I[i] * e * dt_s, -limit[i], limit[i]);
    }
  }
  return torque;
}

}  // namespace hitl::flight
