#include "engine/sensors/imu.h"

#include <algorithm>
#include <cmath>

#include "engine/frames/frames.h"
#include "engine/model/atmosphere.h"

namespace hitl::sensors {

void quantise(Eigen::Vector3d& v, double resolution) {
  if (!(resolution > 0.0)) return;
  for (int i = 0; i < 3; ++i) v[i] = std::round(v[i] / resolution) * resolution;
}

bool saturate(Eigen::Vector3d& v, double range) {
  if (!(range > 0.0)) return false;  // a config built in code without a range: no limit
  const double full_scale = range * 32767.0 / 32768.0;
  bool clipped = false;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(v[i]) > full_scale) {
      v[i] = std::clamp(v[i], -full_scale, full_scale);
      clipped = true;
    }
  }
  return clipped;
}

Imu::Imu(const model::ImuConfig& config, const model::WorldConfig& world, std::uint64_t seed)
    : config_(config),
      world_(world),
      accel_noise_(config.accel, config.rate_hz, seed, "imu.accel"),
      gyro_noise_(config.gyro, config.rate_hz, seed, "imu.gyro"),
      vibration_(config.vibration, seed, config.filter) {}

void Imu::reset() {
  accel_noise_.reset();
  gyro_noise_.reset();
  vibration_.reset();
  last_t_s_ = -1.0;
}

ImuSample Imu::sample(const model::VehicleState& state, double t_s) {
  const double dt_s = sample_interval_s(last_t_s_, t_s, config_.rate_hz);
  const Eigen::Vector3d& r_FLU_m = config_.position_FLU_m;
  const Eigen::Vector3d& w = state.w_step_mean_FLU_rad_s;
  // Specific force at the mount, FLU: lever-arm terms of a rigid body.
  Eigen::Vector3d f_FLU = state.specific_force_FLU_m_s2 + state.alpha_FLU_rad_s2.cross(r_FLU_m) + w.cross(w.cross(r_FLU_m));
  Eigen::Vector3d w_sensed_FLU = w;
  if (vibration_.enabled()) {
    const Shake shake = vibration_.sample(state.rotor_speed_rad_s, dt_s);
    f_FLU += shake.accel_FLU_m_s2;
    w_sensed_FLU += shake.gyro_FLU_rad_s;
  }
  ImuSample s;
  s.time_s = t_s;
  const Eigen::Vector3d accel_FRD_m_s2 = frames::flu_to_frd(f_FLU);
  const Eigen::Vector3d gyro_FRD_rad_s = frames::flu_to_frd(w_sensed_FLU);
  s.accel_FRD_m_s2 = accel_FRD_m_s2 + noise_scale_ * (accel_noise_.apply(accel_FRD_m_s2, dt_s) - accel_FRD_m_s2);
  s.gyro_FRD_rad_s = gyro_FRD_rad_s + noise_scale_ * (gyro_noise_.apply(gyro_FRD_rad_s, dt_s) - gyro_FRD_rad_s);
  quantise(s.accel_FRD_m_s2, config_.accel_resolution_m_s2);
  quantise(s.gyro_FRD_rad_s, config_.gyro_resolution_rad_s);
  if (saturate(s.accel_FRD_m_s2, config_.accel_range_m_s2)) ++saturation_.accel;
  if (saturate(s.gyro_FRD_rad_s, config_.gyro_range_rad_s)) ++saturation_.gyro;
  s.temperature_degC = model::isa_temperature_degC(world_.atmosphere, world_.home.alt_m + state.p_ENU_m.z());
  return s;
}

}  // namespace hitl::sensors
