// One axis of the position/velocity estimate: a linear Kalman filter on x = [p, v, b] (position m,
// velocity m/s, accelerometer bias m/s^2 along the axis), driven by the measured acceleration:
//   p' = v,  v' = a_meas - b + w_a,  b' = w_b
// Measurements of p (GPS, baro) and v (GPS) are gated: test ratio = innov^2 / (gate^2 S), S =
// P_ii + R; above 1 the sample is rejected (reported, not fused).
#pragma once

#include <Eigen/Core>

namespace hitl::flight {

struct Innovation {
  double innovation = 0.0;  ///< measured - predicted
  double variance = 0.0;    ///< S
  double test_ratio = 0.0;
  bool fused = false;
};

class AxisFilter {
 public:
  void reset(double p, double v, double p_var, double v_var, double b_var);
  void predict(double a_meas, double dt_s, double accel_noise, double bias_noise);
  Innovation fuse_position(double p_meas, double noise_var, double gate_sigma);
  Innovation fuse_velocity(double v_meas, double noise_var, double gate_sigma);
  /// Moves the position to p (a reset after a long rejection), keeping the rest.
  void reset_position(double p, double p_var);

  double p() const { return x_[0]; }
  double v() const { return x_[1]; }
  double bias() const { return x_[2]; }
  double p_var() const { return P_(0, 0); }
  double v_var() const { return P_(1, 1); }

 private:
  Innovation fuse(int state, double meas, double noise_var, double gate_sigma);
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d P_ = Eigen::Matrix3d::Identity();
};

}  // namespace hitl::flight
