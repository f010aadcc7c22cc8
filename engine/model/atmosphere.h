// ISA troposphere (x500.md): p = p0 (1 - L h / T0)^5.25588, T = T0 - L h, L = 0.0065 K/m,
// h the altitude above mean sea level. With the defaults p0 = 101325 Pa, T0 = 288.15 K this is
// p = 101325 (1 - 2.25577e-5 h)^5.25588.
#pragma once

#include "engine/model/world_config.h"

namespace hitl::model {

inline constexpr double kIsaLapseRate_K_m = 0.0065;
inline constexpr double kIsaPressureExponent = 5.25588;  // g0 M / (R L)
inline constexpr double kCelsiusToKelvin = 273.15;

double isa_pressure_Pa(const AtmosphereConfig& atmosphere, double alt_msl_m);
double isa_temperature_degC(const AtmosphereConfig& atmosphere, double alt_msl_m);
/// The altitude at which the ISA pressure is `pressure_Pa` (inverse of isa_pressure_Pa).
double isa_altitude_m(const AtmosphereConfig& atmosphere, double pressure_Pa);

}  // namespace hitl::model
