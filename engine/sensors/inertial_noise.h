// Three-axis sensor noise as the Gazebo IMU plugin models it, per axis:
//   bias <- phi bias + sigma_b N(0,1),  phi = exp(-dt/tau),
//           sigma_b^2 = random_walk^2 tau / 2 (1 - exp(-2 dt / tau))        (Gauss-Markov)
//   out = truth + bias + turn_on_bias + (noise_density * sqrt(rate)) N(0,1)
// The turn-on bias is drawn once per axis at construction (and reset).
#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "engine/model/random_stream.h"
#include "engine/model/vehicle_config.h"

namespace hitl::sensors {

class InertialNoise {
 public:
  /// `rate_hz`: the sample rate, which sets the white noise sigma; `stream`: the name of the RNG stream.
  InertialNoise(const model::InertialNoiseConfig& config, double rate_hz, std::uint64_t seed, std::string stream);
  /// Truth plus noise for a sample taken dt after the previous one.
  Eigen::Vector3d apply(const Eigen::Vector3d& truth, double dt_s);
  void reset();

  const Eigen::Vector3d& bias() const { return bias_; }
  const Eigen::Vector3d& turn_on_bias() const { return turn_on_bias_; }
  /// Standard deviation of the white noise per sample: density * sqrt(rate).
  double white_sigma() const { return white_sigma_; }

 private:
  model::InertialNoiseConfig config_;
  double white_sigma_;
  std::uint64_t seed_;
  std::string stream_;
  model::RandomStream rng_;
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d turn_on_bias_ = Eigen::Vector3d::Zero();
};

}  // namespace hitl::sensors
