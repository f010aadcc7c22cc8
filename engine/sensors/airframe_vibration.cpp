#include "engine/sensors/airframe_vibration.h"

#include <cmath>
#include <numbers>

#include "engine/model/random_stream.h"

namespace hitl::sensors {

AirframeVibration::AirframeVibration(const model::VibrationConfig& config, std::uint64_t seed) : config_(config), seed_(seed) {
  reset();
}

bool AirframeVibration::enabled() const {
  return config_.imbalance_m_s2_per_rad2_s2 != 0.0 || config_.blade_pass_m_s2_per_rad2_s2 != 0.0 ||
         config_.gyro_imbalance_rad_s_per_rad2_s2 != 0.0;
}

void AirframeVibration::reset() {
  model::RandomStream rng(seed_, "imu.vibration");
  // Uniform in [0, 2 pi): the normal draw through its own distribution function.
  for (double& p : phase_rad_) p = 2.0 * std::numbers::pi * (0.5 + 0.5 * std::erf(rng.normal() / std::numbers::sqrt2));
}

Eigen::Vector2d AirframeVibration::mean_cos_sin(double phi0, double d) {
  if (std::abs(d) < 1e-9) return {std::cos(phi0), std::sin(phi0)};
  return {(std::sin(phi0 + d) - std::sin(phi0)) / d, (std::cos(phi0) - std::cos(phi0 + d)) / d};
}

Shake AirframeVibration::sample(const std::array<double, 4>& rotor_speed_rad_s, double dt_s) {
  Shake out;
  if (!enabled()) return out;
  const double blades = static_cast<double>(config_.blades);
  for (std::size_t i = 0; i < phase_rad_.size(); ++i) {
    const double w = rotor_speed_rad_s[i];
    const double w2 = w * w;
    const double d = w * dt_s;
    const Eigen::Vector2d once = mean_cos_sin(phase_rad_[i], d);                 // at the rotor's frequency
    const Eigen::Vector2d blade_pass = mean_cos_sin(blades * phase_rad_[i], blades * d);  // at blades x it
    out.accel_FLU_m_s2.x() += config_.imbalance_m_s2_per_rad2_s2 * w2 * once.x();
    out.accel_FLU_m_s2.y() += config_.imbalance_m_s2_per_rad2_s2 * w2 * once.y();
    out.accel_FLU_m_s2.z() += config_.blade_pass_m_s2_per_rad2_s2 * w2 * blade_pass.x();
    out.gyro_FLU_rad_s.x() += config_.gyro_imbalance_rad_s_per_rad2_s2 * w2 * once.x();
    out.gyro_FLU_rad_s.y() += config_.gyro_imbalance_rad_s_per_rad2_s2 * w2 * once.y();
    phase_rad_[i] = std::fmod(phase_rad_[i] + d, 2.0 * std::numbers::pi);
  }
  return out;
}

}  // namespace hitl::sensors
