#include "engine/sensors/magnetometer.h"

#include <cmath>
#include <numbers>

#include "engine/frames/frames.h"

namespace hitl::sensors {

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
  s.mag_FRD_gauss = noise_.apply(q_FRD_to_NED.conjugate() * field_NED_gauss_, dt_s);
  return s;
}

}  // namespace hitl::sensors
