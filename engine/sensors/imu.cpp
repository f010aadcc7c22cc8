#include "engine/sensors/imu.h"

#include "engine/frames/frames.h"
#include "engine/model/atmosphere.h"

namespace hitl::sensors {

Imu::Imu(const model::ImuConfig& config, const model::WorldConfig& world, std::uint64_t seed)
    : config_(config),
      world_(world),
      accel_noise_(config.accel, config.rate_hz, seed, "imu.accel"),
      gyro_noise_(config.gyro, config.rate_hz, seed, "imu.gyro") {}

void Imu::reset() {
  accel_noise_.reset();
  gyro_noise_.reset();
  last_t_s_ = -1.0;
}

ImuSample Imu::sample(const model::VehicleState& state, double t_s) {
  const double dt_s = sample_interval_s(last_t_s_, t_s, config_.rate_hz);
  const Eigen::Vector3d& r_FLU_m = config_.position_FLU_m;
  const Eigen::Vector3d& w = state.w_FLU_rad_s;
  // Specific force at the mount, FLU: lever-arm terms of a rigid body.
  const Eigen::Vector3d f_FLU = state.specific_force_FLU_m_s2 + state.alpha_FLU_rad_s2.cross(r_FLU_m) + w.cross(w.cross(r_FLU_m));
  ImuSample s;
  s.time_s = t_s;
  s.accel_FRD_m_s2 = accel_noise_.apply(frames::flu_to_frd(f_FLU), dt_s);
  s.gyro_FRD_rad_s = gyro_noise_.apply(frames::flu_to_frd(w), dt_s);
  s.temperature_c = model::isa_temperature_c(world_.atmosphere, world_.home.alt_m + state.p_ENU_m.z());
  return s;
}

}  // namespace hitl::sensors
