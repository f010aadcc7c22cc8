#include "emulator/flight/axis_filter.h"

namespace hitl::flight {

void AxisFilter::reset(double p, double v, double p_var, double v_var, double b_var) {
  x_ << p, v, 0.0;
  P_.setZero();
  P_.diagonal() << p_var, v_var, b_var;
}

void AxisFilter::predict(double a_meas, double dt_s, double accel_noise, double bias_noise) {
  const double a = a_meas - x_[2];
  x_[0] += x_[1] * dt_s + 0.5 * a * dt_s * dt_s;
  x_[1] += a * dt_s;
  Eigen::Matrix3d F;
  F << 1.0, dt_s, -0.5 * dt_s * dt_s,  //
      0.0, 1.0, -dt_s,                 //
      0.0, 0.0, 1.0;
  const Eigen::Vector3d G(0.5 * dt_s * dt_s, dt_s, 0.0);
  P_ = F * P_ * F.transpose() + G * G.transpose() * (accel_noise * accel_noise);
  P_(2, 2) += bias_noise * bias_noise * dt_s;
  P_ = 0.5 * (P_ + P_.transpose());
}

Innovation AxisFilter::fuse(int state, double meas, double noise_var, double gate_sigma) {
  Innovation r;
  r.innovation = meas - x_[state];
  r.variance = P_(state, state) + noise_var;
  r.test_ratio = r.innovation * r.innovation / (gate_sigma * gate_sigma * r.variance);
  if (r.test_ratio > 1.0) return r;
  const Eigen::Vector3d K = P_.col(state) / r.variance;
  x_ += K * r.innovation;
  P_ -= K * P_.row(state);
  P_ = 0.5 * (P_ + P_.transpose());
  r.fused = true;
  return r;
}

Innovation AxisFilter::fuse_position(double p_meas, double noise_var, double gate_sigma) {
  return fuse(0, p_meas, noise_var, gate_sigma);
}

Innovation AxisFilter::fuse_velocity(double v_meas, double noise_var, double gate_sigma) {
  return fuse(1, v_meas, noise_var, gate_sigma);
}

void AxisFilter::reset_position(double p, double p_var) {
  x_[0] = p;
  P_.row(0).setZero();
  P_.col(0).setZero();
  P_(0, 0) = p_var;
}

}  // namespace hitl::flight
