#include "engine/sensors/barometer.h"

#include <cmath>

#include "engine/model/atmosphere.h"

namespace hitl::sensors {

Barometer::Barometer(const model::BaroConfig& config, const model::WorldConfig& world, std::uint64_t seed)
    : config_(config), world_(world), seed_(seed), rng_(seed, "baro") {}

void Barometer::reset() {
  rng_ = model::RandomStream(seed_, "baro");
  drift_Pa_ = 0.0;
  last_t_s_ = -1.0;
}

BaroSample Barometer::sample(const model::VehicleState& state, double t_s) {
  const double dt_s = sample_interval_s(last_t_s_, t_s, config_.rate_hz);
  const double alt_msl_m = world_.home.alt_m + state.p_ENU_m.z();
  drift_Pa_ += rng_.normal(config_.drift_pa_sqrt_s * std::sqrt(dt_s));
  BaroSample s;
  s.time_s = t_s;
  s.pressure_Pa = model::isa_pressure_Pa(world_.atmosphere, alt_msl_m) + drift_Pa_ + rng_.normal(config_.noise_pa);
  s.temperature_degC = model::isa_temperature_degC(world_.atmosphere, alt_msl_m) + rng_.normal(config_.temperature_noise_c);
  s.pressure_alt_m = model::isa_altitude_m(world_.atmosphere, s.pressure_Pa);
  return s;
}

}  // namespace hitl::sensors
