#include "engine/model/atmosphere.h"

#include <cmath>

namespace hitl::model {

double isa_pressure_Pa(const AtmosphereConfig& a, double alt_msl_m) {
  const double T0_K = a.sea_level_temperature_c + kCelsiusToKelvin;
  return a.sea_level_pressure_pa * std::pow(1.0 - kIsaLapseRate_K_m * alt_msl_m / T0_K, kIsaPressureExponent);
}

double isa_temperature_degC(const AtmosphereConfig& a, double alt_msl_m) {
  return a.sea_level_temperature_c - kIsaLapseRate_K_m * alt_msl_m;
}

double isa_altitude_m(const AtmosphereConfig& a, double pressure_Pa) {
  const double T0_K = a.sea_level_temperature_c + kCelsiusToKelvin;
  return T0_K / kIsaLapseRate_K_m * (1.0 - std::pow(pressure_Pa / a.sea_level_pressure_pa, 1.0 / kIsaPressureExponent));
}

}  // namespace hitl::model
