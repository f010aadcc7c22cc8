// Accelerometer + gyroscope at the IMU mount (x500: base origin).
//   accel_FRD = sat( q( noise( FRD( f + alpha x r + w x (w x r) ) ) ) )   f: specific force at the base
//   gyro_FRD  = sat( q( noise( FRD( w ) ) ) )                           origin, r = mount (FLU)
// The rotors' vibration (airframe_vibration.h, off by default) adds to f and w before the noise.
// noise(): inertial_noise.h (scale and cross-axis error, biases, white noise); q() rounds each axis
// to the part's LSB (`*_resolution`, 0: not rounded), as its register holds whole counts.
// f and w are the means over the physics step (VehicleState), as an IMU's output filter averages
// between two readings. sat() clips each axis at the configured full scale, as the sensor's 16-bit
// register does (the largest count, 32767/32768 of the range: ICM-42688 at +-16 g reads at most
// 15.9995 g), and such samples are counted. Level at rest: accel (0, 0, -g). Temperature: ISA at
// the vehicle's altitude.
#pragma once

#include <cstdint>

#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/airframe_vibration.h"
#include "engine/sensors/inertial_noise.h"
#include "engine/sensors/samples.h"

namespace hitl::sensors {

/// Samples with at least one axis clipped at full scale, since construction (resets keep them).
struct ImuSaturation {
  uint64_t accel = 0;
  uint64_t gyro = 0;
};

class Imu {
 public:
  Imu(const model::ImuConfig& config, const model::WorldConfig& world, std::uint64_t seed);
  ImuSample sample(const model::VehicleState& state, double t_s);
  void reset();
  double rate_hz() const { return config_.rate_hz; }
  const InertialNoise& accel_noise() const { return accel_noise_; }
  const InertialNoise& gyro_noise() const { return gyro_noise_; }
  const ImuSaturation& saturation() const { return saturation_; }
  /// The errors against truth (noise and bias walk) x k in the next samples (the imu-noise fault;
  /// 1: as configured). The noise processes draw as before: only what is reported changes.
  void set_noise_scale(double k) { noise_scale_ = k; }

 private:
  model::ImuConfig config_;
  model::WorldConfig world_;
  InertialNoise accel_noise_;
  InertialNoise gyro_noise_;
  AirframeVibration vibration_;
  double last_t_s_ = -1.0;
  ImuSaturation saturation_;
  double noise_scale_ = 1.0;
};

/// Rounds each axis to a whole multiple of `resolution` (one LSB); 0 leaves it.
void quantise(Eigen::Vector3d& v, double resolution);

/// Clips each axis to +-the largest 16-bit count of `range` (range * 32767 / 32768); true when any was.
/// A range of 0 (a config built in code without one) clips nothing.
bool saturate(Eigen::Vector3d& v, double range);

}  // namespace hitl::sensors
