// The airframe's vibration at the IMU, from the rotors (model::VibrationConfig): per rotor an
// imbalance turning with it and a blade-pass ripple along its axis, their amplitudes growing as the
// rotor speed squared, as an imbalance force does. Each rotor's phase advances by its speed over
// each interval; a sample is the vibration's mean over the interval since the previous one (the IMU's
// output averages between readings: a boxcar, whose sinc response attenuates lines near and above
// the sample rate, and whose residue aliases as a real sampled IMU's would). Initial phases are
// drawn from the seed (stream "imu.vibration"): four rotors at one speed do not cancel or add up
// by construction.
#pragma once

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "engine/model/vehicle_config.h"

namespace hitl::sensors {

struct Shake {
  Eigen::Vector3d accel_FLU_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_FLU_rad_s = Eigen::Vector3d::Zero();
};

class AirframeVibration {
 public:
  AirframeVibration(const model::VibrationConfig& config, std::uint64_t seed);
  /// The mean shake over the `dt_s` just past, the rotors at `rotor_speed_rad_s` (their phases advance).
  Shake sample(const std::array<double, 4>& rotor_speed_rad_s, double dt_s);
  void reset();
  bool enabled() const;
  /// The mean of cos(phi) and of sin(phi) as phi goes from phi0 by d (cos, sin of phi0 when d = 0).
  static Eigen::Vector2d mean_cos_sin(double phi0, double d);

 private:
  model::VibrationConfig config_;
  std::uint64_t seed_;
  std::array<double, 4> phase_rad_{};
};

}  // namespace hitl::sensors
