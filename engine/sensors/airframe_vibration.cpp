#include "engine/sensors/airframe_vibration.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/model/random_stream.h"

namespace hitl::sensors {

AirframeVibration::AirframeVibration(const model::VibrationConfig& config, std::uint64_t seed, const model::ImuFilterConfig& filter)
    : config_(config), filter_(filter), seed_(seed) {
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

Eigen::Vector2d AirframeVibration::mean_cos_sin_sampled(double phi0, double d, double n) {
  // sum_{k=1..n} e^{i(phi0 + k delta)} = e^{i(phi0 + (n+1) delta/2)} sin(n delta/2) / sin(delta/2).
  const double delta = d / n;
  const double half_sin = std::sin(delta / 2.0);
  const double centre = phi0 + (n + 1.0) * delta / 2.0;
  if (std::abs(half_sin) < 1e-12)  // every sample at one phase (modulo 2 pi): the line reads as a constant
    return {std::cos(phi0 + delta), std::sin(phi0 + delta)};
  const double gain = std::sin(n * delta / 2.0) / (n * half_sin);
  return gain * Eigen::Vector2d(std::cos(centre), std::sin(centre));
}

std::complex<double> AirframeVibration::filter_response(const model::ImuFilterConfig& filter, double omega_rad_s) {
  std::complex<double> h = 1.0;
  if (filter.anti_alias_hz > 0.0) {  // second order, Butterworth: 1 / (1 - x^2 + i sqrt2 x), x = omega / omega_c
    const double x = omega_rad_s / (2.0 * std::numbers::pi * filter.anti_alias_hz);
    h /= std::complex<double>(1.0 - x * x, std::numbers::sqrt2 * x);
  }
  if (filter.ui_filter_hz > 0.0) h /= std::complex<double>(1.0, omega_rad_s / (2.0 * std::numbers::pi * filter.ui_filter_hz));
  return h;
}

Eigen::Vector2d AirframeVibration::line(double phi0, double d, double dt_s) const {
  if (!(filter_.output_data_rate_hz > 0.0)) return mean_cos_sin(phi0, d);
  const std::complex<double> h = dt_s > 0.0 ? filter_response(filter_, d / dt_s) : std::complex<double>(1.0);
  const double n = std::max(1.0, std::round(dt_s * filter_.output_data_rate_hz));
  return std::abs(h) * mean_cos_sin_sampled(phi0 + std::arg(h), d, n);
}

Shake AirframeVibration::sample(const std::array<double, 4>& rotor_speed_rad_s, double dt_s) {
  Shake out;
  if (!enabled()) return out;
  const double blades = static_cast<double>(config_.blades);
  for (std::size_t i = 0; i < phase_rad_.size(); ++i) {
    const double w = rotor_speed_rad_s[i];
    const double w2 = w * w;
    const double d = w * dt_s;
    const Eigen::Vector2d once = line(phase_rad_[i], d, dt_s);                           // at the rotor's frequency
    const Eigen::Vector2d blade_pass = line(blades * phase_rad_[i], blades * d, dt_s);  // at blades x it
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
