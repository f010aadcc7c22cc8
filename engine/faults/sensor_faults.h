// The sensor faults applied where a real sensor goes wrong: to what it reports, after the sensor
// model sampled the truth (imu-noise and gps-noise act inside the sensor models: the session sets
// their noise scale before sampling). In this order:
//   IMU:  accel_FRD += accel_bias + sum of vibrations A (cos 2 pi f t, sin 2 pi f t, 0)
//                    + sum of prop-damage imbalances A (cos phi_i, sin phi_i, 0), phi_i rotor i's angle
//         gyro_FRD  += gyro_bias;  both clipped at +-the imu-clip range;  stuck: the last reading
//   mag:  mag_FRD = mag_FRD x mag_scale + mag_offset;  stuck: the last reading
//   baro: pressure += baro_offset_Pa, pressure_alt = ISA altitude of that pressure;  stuck: the last
//   GPS:  none under gps-loss; lat/lon moved by (north_m, east_m) on the WGS-84 ellipsoid
//         (meridian and prime-vertical radii at the fix's latitude), v_NED += gps-drift's rate;
//         gps-degrade's report replaces fix_type, satellites, eph and epv.
// "The last reading" is what the sensor reported (with its faults) in the sample before the stuck
// fault started; the sample times go on.
#pragma once

#include <array>
#include <optional>

#include "engine/faults/fault_schedule.h"
#include "engine/model/world_config.h"
#include "engine/sensors/sensor_suite.h"

namespace hitl::faults {

class SensorFaults {
 public:
  explicit SensorFaults(const model::AtmosphereConfig& atmosphere) : atmosphere_(atmosphere) {}
  /// Applies `active` to the samples in `frame` at simulated time `t_s` (called every step: the
  /// rotors' angles integrate `rotor_speed_rad_s` over time).
  void apply(const ActiveFaults& active, double t_s, sensors::SensorFrame& frame,
             const std::array<double, 4>& rotor_speed_rad_s = {});

 private:
  model::AtmosphereConfig atmosphere_;
  std::array<double, 4> rotor_angle_rad_{};
  double last_t_s_ = -1;
  std::optional<sensors::ImuSample> last_imu_, held_imu_;
  std::optional<sensors::MagSample> last_mag_, held_mag_;
  std::optional<sensors::BaroSample> last_baro_, held_baro_;
};

/// `lat_deg`, `lon_deg` moved `north_m` and `east_m` (WGS-84; exact to millimetres over kilometres).
void offset_lat_lon(double& lat_deg, double& lon_deg, double north_m, double east_m);

}  // namespace hitl::faults
