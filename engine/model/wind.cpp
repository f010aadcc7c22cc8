#include "engine/model/wind.h"

namespace hitl::model {

Wind::Wind(const WindConfig& config, std::uint64_t seed) : config_(config), seed_(seed), rng_(seed, "wind") {}

Eigen::Vector3d Wind::advance(double dt_s) {
  for (int i = 0; i < 3; ++i) {
    const double sigma = config_.gust_sigma_m_s[i];
    if (sigma == 0.0) continue;
    const double tau_s = config_.gust_correlation_time_s;
    gust_ENU_m_s_[i] = gauss_markov_step(gust_ENU_m_s_[i], dt_s, tau_s, random_walk_for_stationary_sigma(sigma, tau_s), rng_);
  }
  return velocity_ENU_m_s();
}

void Wind::reset() {
  rng_ = RandomStream(seed_, "wind");
  gust_ENU_m_s_.setZero();
}

}  // namespace hitl::model
