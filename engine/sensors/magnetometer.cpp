#include "engine/sensors/magnetometer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/frames/frames.h"

namespace hitl::sensors {
namespace {

/// Rounded to whole LSBs and held within the full scale, as the part's registers give it (0: none).
Eigen::Vector3d as_read(Eigen::Vector3d v, const model::MagConfig& config) {
  for (int i = 0; i < 3; ++i) {
    if (config.resolution_gauss > 0.0) v[i] = std::round(v[i] / config.resolution_gauss) * config.resolution_gauss;
    if (config.range_gauss > 0.0) v[i] = std::clamp(v[i], -config.range_gauss, config.range_gauss);
  }
  return v;
}

}  // namespace

Eigen::Vector3d earth_field_NED_gauss(const model::MagneticFieldConfig& field) {
  const double deg = std::numbers::pi / 180.0;
  const double decl = field.declination_deg * deg;
  const double incl = field.inclination_deg * deg;
  const double horizontal = field.strength_gauss * std::cos(incl);
  return {horizontal * std::cos(decl), horizontal * std::sin(decl), field.strength_gauss * std::sin(incl)};
}

Magnetometer::Magnetometer(const model::MagConfig& config, const model::MagneticFieldConfig& field, std::uint64_t seed)
    : config_(config), field_NED_gauss_(earth_field_NED_gauss(field)), noise_(config.noise, config.rate_hz, seed, "mag") {}

void Magnetometer::reset() {
  noise_.reset();
  last_t_s_ = -1.0;
}

MagSample Magnetometer::sample(const model::VehicleState& state, double t_s) {
  const double dt_s = sample_interval_s(last_t_s_, t_s, config_.rate_hz);
  const Eigen::Quaterniond q_FRD_to_NED = frames::q_FRD_to_NED_from(state.q_FLU_to_ENU);
  MagSample s;
  s.time_s = t_s;
  s.mag_FRD_gauss = as_read(noise_.apply(q_FRD_to_NED.conjugate() * field_NED_gauss_, dt_s), config_);
  return s;
}

}  // namespace hitl::sensors
