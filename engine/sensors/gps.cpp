#include "engine/sensors/gps.h"

#include <cmath>
#include <numbers>

#include "engine/frames/frames.h"

namespace hitl::sensors {

Gps::Gps(const model::GpsConfig& config, const model::HomeConfig& home, std::uint64_t seed)
    : config_(config), geodesy_(home), seed_(seed), rng_(seed, "gps") {}

void Gps::reset() {
  rng_ = model::RandomStream(seed_, "gps");
  error_ENU_m_.setZero();
  last_t_s_ = -1.0;
  pending_.clear();
}

GpsSample Gps::measure(const model::VehicleState& state, double t_s) {
  const double dt_s = sample_interval_s(last_t_s_, t_s, config_.rate_hz);
  const double tau_s = config_.error_correlation_time_s;
  const double sigmas_m[3] = {config_.horizontal_error_sigma_m, config_.horizontal_error_sigma_m,
                              config_.vertical_error_sigma_m};
  const double white_m[3] = {config_.horizontal_noise_m, config_.horizontal_noise_m, config_.vertical_noise_m};
  Eigen::Vector3d p_ENU_m = state.p_ENU_m;
  for (int i = 0; i < 3; ++i) {
    if (sigmas_m[i] != 0.0) {
      error_ENU_m_[i] = model::gauss_markov_step(error_ENU_m_[i], dt_s, tau_s,
                                                 model::random_walk_for_stationary_sigma(sigmas_m[i], tau_s), rng_);
    }
    p_ENU_m[i] += noise_scale_ * (error_ENU_m_[i] + rng_.normal(white_m[i]));
  }
  const Geodetic g = geodesy_.to_geodetic(p_ENU_m);
  GpsSample s;
  s.time_s = t_s;
  s.lat_deg = g.lat_deg;
  s.lon_deg = g.lon_deg;
  s.alt_m = g.alt_m;
  s.v_NED_m_s = frames::enu_to_ned(state.v_ENU_m_s);
  for (int i = 0; i < 3; ++i) s.v_NED_m_s[i] += noise_scale_ * rng_.normal(config_.velocity_noise_m_s);
  s.ground_speed_m_s = s.v_NED_m_s.head<2>().norm();
  s.course_over_ground_deg = course_over_ground_deg(s.v_NED_m_s);
  if (config_.accuracy_follows_error) {  // the receiver's estimate moves with its error
    const double wh = config_.horizontal_noise_m, wv = config_.vertical_noise_m;
    s.eph_m = noise_scale_ * std::sqrt(error_ENU_m_.head<2>().squaredNorm() + 2.0 * wh * wh);
    s.epv_m = noise_scale_ * std::sqrt(error_ENU_m_.z() * error_ENU_m_.z() + wv * wv);
  } else {
    s.eph_m = config_.eph_m;
    s.epv_m = config_.epv_m;
  }
  s.fix_type = 3;
  s.satellites = static_cast<std::uint8_t>(config_.satellites);
  return s;
}

double course_over_ground_deg(const Eigen::Vector3d& v_NED_m_s) {
  const double cog_deg = std::atan2(v_NED_m_s.y(), v_NED_m_s.x()) * 180.0 / std::numbers::pi;
  return cog_deg < 0.0 ? cog_deg + 360.0 : cog_deg;
}

GpsSample Gps::sample(const model::VehicleState& state, double t_s) {
  GpsSample fresh = measure(state, t_s);
  if (config_.delay_s <= 0.0) return fresh;
  pending_.push_back(fresh);
  // Report the newest fix that is at least delay_s old; before there is one, the oldest.
  while (pending_.size() > 1 && pending_[1].time_s <= t_s - config_.delay_s + 1e-9) pending_.pop_front();
  return pending_.front();
}

}  // namespace hitl::sensors
