// Three-axis sensor noise, per axis (the Gazebo IMU plugin's model, plus a bias instability and a
// scale and cross-axis error):
//   bias <- phi bias + sigma_b N(0,1),  phi = exp(-dt/tau),
//           sigma_b^2 = random_walk^2 tau / 2 (1 - exp(-2 dt / tau))        (Gauss-Markov)
//   flicker = sum_k f_k,  f_k Gauss-Markov with tau_k = 0.1, 1, 10, 100, 1000 s and stationary
//           sigma_k^2 = B^2 ln(10) / pi: one process per decade sums to a 1/f spectrum over
//           ~0.3-300 s, so the Allan deviation is flat at 0.664 B there (IEEE 952's bias
//           instability B; each f_k starts at a stationary draw)
//   out = M truth + bias + flicker + turn_on_bias + (noise_density * sqrt(rate)) N(0,1)
//   M = I + diag(scale errors) + off-diagonal cross-axis sensitivities, drawn once
// The turn-on bias and M are drawn at construction (and reset); M and the flicker processes from
// their own streams, so a config without them draws exactly as before.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "engine/model/random_stream.h"
#include "engine/model/vehicle_config.h"

namespace hitl::sensors {

/// The flicker approximation's correlation times [s], one per decade.
inline constexpr std::array<double, 5> kBiasInstabilityTimes_s{0.1, 1.0, 10.0, 100.0, 1000.0};

/// Stationary sigma of each flicker process for bias instability B (sigma_k^2 = B^2 ln 10 / pi).
double bias_instability_process_sigma(double bias_instability);

class InertialNoise {
 public:
  /// `rate_hz`: the sample rate, which sets the white noise sigma; `stream`: the name of the RNG stream.
  InertialNoise(const model::InertialNoiseConfig& config, double rate_hz, std::uint64_t seed, std::string stream);
  /// Truth plus noise for a sample taken dt after the previous one.
  Eigen::Vector3d apply(const Eigen::Vector3d& truth, double dt_s);
  void reset();

  const Eigen::Vector3d& bias() const { return bias_; }
  const Eigen::Vector3d& turn_on_bias() const { return turn_on_bias_; }
  /// The scale and cross-axis matrix M (identity without those errors).
  const Eigen::Matrix3d& misalignment() const { return misalignment_; }
  /// Standard deviation of the white noise per sample: density * sqrt(rate).
  double white_sigma() const { return white_sigma_; }

 private:
  model::InertialNoiseConfig config_;
  double white_sigma_;
  std::uint64_t seed_;
  std::string stream_;
  model::RandomStream rng_;
  model::RandomStream flicker_rng_;
  Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d turn_on_bias_ = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, kBiasInstabilityTimes_s.size()> flicker_{};
  std::array<double, kBiasInstabilityTimes_s.size()> flicker_random_walk_{};  ///< each process's driving density
  Eigen::Matrix3d misalignment_ = Eigen::Matrix3d::Identity();
};

}  // namespace hitl::sensors
