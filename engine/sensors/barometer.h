// Barometer: ISA pressure and temperature at the vehicle's altitude (home altitude + ENU z),
// plus white noise and an optional random-walk drift:
//   pressure = p_ISA(h) + drift + noise_pa N(0,1),   drift <- drift + drift_pa_sqrt_s sqrt(dt) N(0,1)
#pragma once

#include <cstdint>

#include "engine/model/random_stream.h"
#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/samples.h"

namespace hitl::sensors {

class Barometer {
 public:
  Barometer(const model::BaroConfig& config, const model::WorldConfig& world, std::uint64_t seed);
  BaroSample sample(const model::VehicleState& state, double t_s);
  void reset();
  double rate_hz() const { return config_.rate_hz; }

 private:
  model::BaroConfig config_;
  model::WorldConfig world_;
  std::uint64_t seed_;
  model::RandomStream rng_;
  double drift_Pa_ = 0.0;
  double last_t_s_ = -1.0;
};

}  // namespace hitl::sensors
