// Accelerometer + gyroscope at the IMU mount (x500: base origin).
//   accel_FRD = FRD( f_o + alpha x r + w x (w x r) ) + noise     f_o = R^T (a_o - g): specific force
//   gyro_FRD  = FRD( w ) + noise                                  at the base origin, r = mount (FLU)
// Level at rest: accel (0, 0, -g). Temperature: ISA at the vehicle's altitude.
#pragma once

#include <cstdint>

#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"
#include "engine/sensors/inertial_noise.h"
#include "engine/sensors/samples.h"

namespace hitl::sensors {

class Imu {
 public:
  Imu(const model::ImuConfig& config, const model::WorldConfig& world, std::uint64_t seed);
  ImuSample sample(const model::VehicleState& state, double t_s);
  void reset();
  double rate_hz() const { return config_.rate_hz; }
  const InertialNoise& accel_noise() const { return accel_noise_; }
  const InertialNoise& gyro_noise() const { return gyro_noise_; }

 private:
  model::ImuConfig config_;
  model::WorldConfig world_;
  InertialNoise accel_noise_;
  InertialNoise gyro_noise_;
  double last_t_s_ = -1.0;
};

}  // namespace hitl::sensors
