// The flight stack's estimate against the simulator's ground truth, which only HITL can show:
// position (LOCAL_POSITION_NED, from the estimator's origin) against the truth from the vehicle's
// rest pose at home (where the estimator set its origin), and attitude (ATTITUDE_QUATERNION)
// against the true attitude, as the angle of the rotation between them.
#pragma once

#include <array>
#include <cstdint>

namespace hitl::telemetry {

/// The simulator's truth at one instant.
struct TruthPose {
  double sim_time_s = 0;
  std::array<double, 3> p_NED_m{};                ///< base origin from its rest pose at home
  std::array<double, 4> q_FRD_to_NED{1, 0, 0, 0};  ///< w, x, y, z
};

struct EstimateError {
  uint64_t position_samples = 0;
  uint64_t attitude_samples = 0;
  double horizontal_m = 0;      ///< latest
  double vertical_m = 0;        ///< latest, estimate minus truth, down positive
  double attitude_deg = 0;      ///< latest
  double horizontal_rms_m = 0;  ///< since the start
  double attitude_rms_deg = 0;
};

/// The angle of the rotation from one attitude to the other, degrees (0..180); either sign of a
/// quaternion is the same attitude.
double attitude_difference_deg(const std::array<double, 4>& q_a, const std::array<double, 4>& q_b);

class EstimateErrorMeter {
 public:
  void on_position(const std::array<double, 3>& estimate_NED_m, const TruthPose& truth);
  void on_attitude(const std::array<double, 4>& estimate_q_FRD_to_NED, const TruthPose& truth);
  const EstimateError& error() const { return error_; }

 private:
  EstimateError error_;
  double horizontal_sum_sq_ = 0;
  double attitude_sum_sq_ = 0;
};

}  // namespace hitl::telemetry
