#include "engine/telemetry/estimate_error.h"

#include <algorithm>
#include <cmath>

namespace hitl::telemetry {

double attitude_difference_deg(const std::array<double, 4>& q_a, const std::array<double, 4>& q_b) {
  const double norm_a = std::sqrt(q_a[0] * q_a[0] + q_a[1] * q_a[1] + q_a[2] * q_a[2] + q_a[3] * q_a[3]);
  const double norm_b = std::sqrt(q_b[0] * q_b[0] + q_b[1] * q_b[1] + q_b[2] * q_b[2] + q_b[3] * q_b[3]);
  if (!(norm_a > 0) || !(norm_b > 0)) return NAN;
  double dot = 0;
  for (std::size_t i = 0; i < 4; ++i) dot += q_a[i] * q_b[i];
  dot = std::min(1.0, std::fabs(dot) / (norm_a * norm_b));
  return 2.0 * std::acos(dot) * 180.0 / M_PI;
}

void EstimateErrorMeter::on_position(const std::array<double, 3>& estimate_NED_m, const TruthPose& truth) {
  const double dn = estimate_NED_m[0] - truth.p_NED_m[0];
  const double de = estimate_NED_m[1] - truth.p_NED_m[1];
  const double dd = estimate_NED_m[2] - truth.p_NED_m[2];
  if (!std::isfinite(dn) || !std::isfinite(de) || !std::isfinite(dd)) return;
  error_.horizontal_m = std::hypot(dn, de);
  error_.vertical_m = dd;
  ++error_.position_samples;
  horizontal_sum_sq_ += error_.horizontal_m * error_.horizontal_m;
  error_.horizontal_rms_m = std::sqrt(horizontal_sum_sq_ / static_cast<double>(error_.position_samples));
}

void EstimateErrorMeter::on_attitude(const std::array<double, 4>& estimate_q_FRD_to_NED, const TruthPose& truth) {
  const double angle_deg = attitude_difference_deg(estimate_q_FRD_to_NED, truth.q_FRD_to_NED);
  if (!std::isfinite(angle_deg)) return;
  error_.attitude_deg = angle_deg;
  ++error_.attitude_samples;
  attitude_sum_sq_ += angle_deg * angle_deg;
  error_.attitude_rms_deg = std::sqrt(attitude_sum_sq_ / static_cast<double>(error_.attitude_samples));
}

}  // namespace hitl::telemetry
