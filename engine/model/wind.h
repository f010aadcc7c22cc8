// Wind: a constant mean plus gusts, each ENU axis a first-order Gauss-Markov process with the
// configured stationary sigma and correlation time, advanced once per outer step from its own
// seeded stream ("wind").
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "engine/model/random_stream.h"
#include "engine/model/world_config.h"

namespace hitl::model {

class Wind {
 public:
  Wind(const WindConfig& config, std::uint64_t seed);
  /// Advances the gusts by dt and returns the air velocity (ENU, m/s) for the coming interval.
  Eigen::Vector3d advance(double dt_s);
  Eigen::Vector3d velocity_ENU_m_s() const { return config_.velocity_ENU_m_s + gust_ENU_m_s_ + event_ENU_m_s_ + turbulence_ENU_m_s_; }
  /// A wind event (the wind, gust and turbulence faults), until changed: an added mean and added
  /// turbulence (each axis Gauss-Markov, its own stream "wind-event"; sigma 0: none).
  void set_event(const Eigen::Vector3d& extra_ENU_m_s, double turbulence_sigma_m_s, double turbulence_tau_s);
  /// Gusts back to zero and the stream back to its seed.
  void reset();

 private:
  WindConfig config_;
  std::uint64_t seed_;
  RandomStream rng_;
  Eigen::Vector3d gust_ENU_m_s_ = Eigen::Vector3d::Zero();
  RandomStream event_rng_;
  Eigen::Vector3d event_ENU_m_s_ = Eigen::Vector3d::Zero();
  double turbulence_sigma_m_s_ = 0;
  double turbulence_tau_s_ = 1;
  Eigen::Vector3d turbulence_ENU_m_s_ = Eigen::Vector3d::Zero();
};

}  // namespace hitl::model
