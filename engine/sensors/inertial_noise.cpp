#include "engine/sensors/inertial_noise.h"

#include <cmath>
#include <numbers>
#include <utility>

namespace hitl::sensors {

double bias_instability_process_sigma(double bias_instability) {
  return bias_instability * std::sqrt(std::log(10.0) / std::numbers::pi);
}

InertialNoise::InertialNoise(const model::InertialNoiseConfig& config, double rate_hz, std::uint64_t seed,
                             std::string stream)
    : config_(config),
      white_sigma_(config.noise_density * std::sqrt(rate_hz)),
      seed_(seed),
      stream_(std::move(stream)),
      rng_(seed, stream_),
      flicker_rng_(seed, stream_ + ".flicker") {
  const double flicker_sigma = bias_instability_process_sigma(config.bias_instability);
  for (std::size_t k = 0; k < flicker_random_walk_.size(); ++k)
    flicker_random_walk_[k] = model::random_walk_for_stationary_sigma(flicker_sigma, kBiasInstabilityTimes_s[k]);
  reset();
}

void InertialNoise::reset() {
  rng_ = model::RandomStream(seed_, stream_);
  bias_.setZero();
  for (int i = 0; i < 3; ++i) turn_on_bias_[i] = rng_.normal(config_.turn_on_bias_sigma);
  flicker_rng_ = model::RandomStream(seed_, stream_ + ".flicker");
  const double flicker_sigma = bias_instability_process_sigma(config_.bias_instability);
  for (Eigen::Vector3d& f : flicker_)
    for (int i = 0; i < 3; ++i) f[i] = flicker_rng_.normal(flicker_sigma);  // stationary from the start
  model::RandomStream scale_rng(seed_, stream_ + ".scale");
  misalignment_.setIdentity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      misalignment_(r, c) += scale_rng.normal(r == c ? config_.scale_error_sigma : config_.cross_axis_sigma);
    }
  }
}

Eigen::Vector3d InertialNoise::apply(const Eigen::Vector3d& truth, double dt_s) {
  const Eigen::Vector3d sensed = misalignment_ * truth;
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (config_.random_walk != 0.0) {
      bias_[i] = model::gauss_markov_step(bias_[i], dt_s, config_.bias_correlation_time_s, config_.random_walk, rng_);
    }
    double flicker = 0.0;
    if (config_.bias_instability != 0.0) {
      for (std::size_t k = 0; k < flicker_.size(); ++k) {
        flicker_[k][i] = model::gauss_markov_step(flicker_[k][i], dt_s, kBiasInstabilityTimes_s[k], flicker_random_walk_[k], flicker_rng_);
        flicker += flicker_[k][i];
      }
    }
    out[i] = sensed[i] + bias_[i] + flicker + turn_on_bias_[i] + rng_.normal(white_sigma_);
  }
  return out;
}

}  // namespace hitl::sensors
