// Where the vehicle flies: gravity, home, Earth's magnetic field, atmosphere, wind, and the
// physics step. The default world is default_world_config() (x500_defaults.cpp).
#pragma once

#include <Eigen/Core>

namespace hitl::model {

/// Origin of the local frame: the ground point under the vehicle at start. World ENU z = 0 is the
/// ground, at alt_m above mean sea level.
struct HomeConfig {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;  ///< MSL altitude of the ground at home (used as ellipsoid height too, as PX4 does)
};

/// Earth's field at home, constant over the flight.
struct MagneticFieldConfig {
  double declination_deg = 0.0;  ///< east of true north positive
  double inclination_deg = 0.0;  ///< below the horizon positive
  double strength_gauss = 0.0;
};

/// ISA troposphere: p = p0 (1 - L h / T0)^5.25588 with L = 0.0065 K/m.
struct AtmosphereConfig {
  double sea_level_pressure_pa = 0.0;
  double sea_level_temperature_c = 0.0;
};

/// Constant wind plus gusts (first-order Gauss-Markov per axis).
struct WindConfig {
  Eigen::Vector3d velocity_ENU_m_s = Eigen::Vector3d::Zero();  ///< air velocity (blowing towards)
  Eigen::Vector3d gust_sigma_m_s = Eigen::Vector3d::Zero();    ///< stationary sigma of the gusts, ENU
  double gust_correlation_time_s = 0.0;
};

struct PhysicsConfig {
  double step_s = 0.0;                  ///< outer step: one step() call
  double max_substep_s = 0.0;           ///< integrator sub-steps are at most this long
  double max_speed_m_s = 0.0;           ///< blow-up detection: linear speed limit
  double max_angular_rate_rad_s = 0.0;  ///< blow-up detection: body angular rate limit
};

struct WorldConfig {
  double gravity_m_s2 = 0.0;
  HomeConfig home;
  MagneticFieldConfig magnetic_field;
  AtmosphereConfig atmosphere;
  WindConfig wind;
  PhysicsConfig physics;
};

}  // namespace hitl::model
