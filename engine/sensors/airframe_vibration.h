// The airframe's vibration at the IMU, from the rotors (model::VibrationConfig): per rotor an
// imbalance turning with it and a blade-pass ripple along its axis, their amplitudes growing as the
// rotor speed squared, as an imbalance force does. Each rotor's phase advances by its speed over
// each interval. A sample is what the IMU outputs of it over the interval since the previous one:
// each line through the part's filter (model::ImuFilterConfig: its gain and phase at the line's
// frequency), then the mean of the part's samples at its output data rate in the interval (as PX4
// integrates a part's FIFO), or, for a part without a filter, the mean over the interval (a boxcar).
// Either mean's sinc-like response attenuates lines near and above the HIL rate, and its residue
// aliases as a real sampled IMU's would. Initial phases are drawn from the seed (stream
// "imu.vibration"): four rotors at one speed do not cancel or add up by construction.
#pragma once

#include <array>
#include <complex>
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
  AirframeVibration(const model::VibrationConfig& config, std::uint64_t seed, const model::ImuFilterConfig& filter = {});
  /// The shake the IMU outputs for the `dt_s` just past, the rotors at `rotor_speed_rad_s` (their phases advance).
  Shake sample(const std::array<double, 4>& rotor_speed_rad_s, double dt_s);
  void reset();
  bool enabled() const;
  /// The mean of cos(phi) and of sin(phi) as phi goes from phi0 by d (cos, sin of phi0 when d = 0).
  static Eigen::Vector2d mean_cos_sin(double phi0, double d);
  /// The mean of cos and sin of phi0 + k d / n for k = 1..n: n samples spread evenly over the step d,
  /// the last at its end (n >= 1).
  static Eigen::Vector2d mean_cos_sin_sampled(double phi0, double d, double n);
  /// The filter's response at `omega_rad_s` (1 where the filter has no stage).
  static std::complex<double> filter_response(const model::ImuFilterConfig& filter, double omega_rad_s);

 private:
  /// One line of phase phi0 advancing by d over the interval, as the part outputs it: (cos, sin) means.
  Eigen::Vector2d line(double phi0, double d, double dt_s) const;

  model::VibrationConfig config_;
  model::ImuFilterConfig filter_;
  std::uint64_t seed_;
  std::array<double, 4> phase_rad_{};
};

}  // namespace hitl::sensors
