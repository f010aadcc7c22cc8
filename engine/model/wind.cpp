#include "engine/model/wind.h"

#include <cmath>

namespace hitl::model {

Wind::Wind(const WindConfig& config, std::uint64_t seed) : config_(config), seed_(seed), rng_(seed, "wind"), event_rng_(seed, "wind-event") {}

void Wind::set_event(const Eigen::Vector3d& extra_ENU_m_s, double turbulence_sigma_m_s, double turbulence_tau_s) {
  event_ENU_m_s_ = extra_ENU_m_s.allFinite() ? extra_ENU_m_s : Eigen::Vector3d::Zero();
  turbulence_sigma_m_s_ = std::isfinite(turbulence_sigma_m_s) && turbulence_sigma_m_s > 0 ? turbulence_sigma_m_s : 0.0;
  turbulence_tau_s_ = std::isfinite(turbulence_tau_s) && turbulence_tau_s > 0 ? turbulence_tau_s : 1.0;
  if (turbulence_sigma_m_s_ == 0.0) turbulence_ENU_m_s_.setZero();
}

Eigen::Vector3d Wind::advance(double dt_s) {
  for (int i = 0; i < 3; ++i) {
    const double sigma = config_.gust_sigma_m_s[i];
    if (sigma == 0.0) continue;
    const double tau_s = config_.gust_correlation_time_s;
    gust_ENU_m_s_[i] = gauss_markov_step(gust_ENU_m_s_[i], dt_s, tau_s, random_walk_for_stationary_sigma(sigma, tau_s), rng_);
  }
  if (turbulence_sigma_m_s_ > 0.0)
    for (int i = 0; i < 3; ++i)
      turbulence_ENU_m_s_[i] = gauss_markov_step(turbulence_ENU_m_s_[i], dt_s, turbulence_tau_s_,
                                                 random_walk_for_stationary_sigma(turbulence_sigma_m_s_, turbulence_tau_s_), event_rng_);
  return velocity_ENU_m_s();
}

void Wind::reset() {
  rng_ = RandomStream(seed_, "wind");
  event_rng_ = RandomStream(seed_, "wind-event");
  gust_ENU_m_s_.setZero();
  turbulence_ENU_m_s_.setZero();
}

}  // namespace hitl::model
