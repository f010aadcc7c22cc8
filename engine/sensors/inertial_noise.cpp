#include "engine/sensors/inertial_noise.h"

#include <cmath>
#include <utility>

namespace hitl::sensors {

InertialNoise::InertialNoise(const model::InertialNoiseConfig& config, double rate_hz, std::uint64_t seed,
                             std::string stream)
    : config_(config),
      white_sigma_(config.noise_density * std::sqrt(rate_hz)),
      seed_(seed),
      stream_(std::move(stream)),
      rng_(seed, stream_) {
  reset();
}

void InertialNoise::reset() {
  rng_ = model::RandomStream(seed_, stream_);
  bias_.setZero();
  for (int i = 0; i < 3; ++i) turn_on_bias_[i] = rng_.normal(config_.turn_on_bias_sigma);
}

Eigen::Vector3d InertialNoise::apply(const Eigen::Vector3d& truth, double dt_s) {
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (config_.random_walk != 0.0) {
      bias_[i] = model::gauss_markov_step(bias_[i], dt_s, config_.bias_correlation_time_s, config_.random_walk, rng_);
    }
    out[i] = truth[i] + bias_[i] + turn_on_bias_[i] + rng_.normal(white_sigma_);
  }
  return out;
}

}  // namespace hitl::sensors
