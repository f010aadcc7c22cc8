#include "engine/model/x500_defaults.h"

#include <cmath>

namespace hitl::model {
namespace {

// x500.md: rotor table (FLU hub positions), all rotors 0.06 m above the base origin.
constexpr double kArm_m = 0.174;
constexpr double kRotorHeight_m = 0.06;

RotorConfig x500_rotor(double x_m, double y_m, Turning turning) {
  RotorConfig r;
  r.position_FLU_m = {x_m, y_m, kRotorHeight_m};
  r.turning = turning;
  r.mass_kg = 0.016076923076923075;
  r.inertia_kgm2 = {3.8464910483993325e-07, 2.6115851691700804e-05, 2.649858234714004e-05};
  r.time_constant_up_s = 0.0125;
  r.time_constant_down_s = 0.025;
  r.max_rot_velocity_rad_s = 1000.0;
  r.motor_constant_N_s2 = 8.54858e-06;
  r.moment_constant_m = 0.016;
  r.rotor_drag_coefficient = 8.06428e-05;
  r.rolling_moment_coefficient = 1e-06;
  r.axial_speed_falloff_m_s = 25.0;  // MulticopterMotorModel: no thrust left at 25 m/s along the axis
  r.input_offset = 0.0;
  r.input_scaling_rad_s = 1000.0;  // PX4 gz x500: motor command 0..1 -> 0..1000 rad/s
  r.zero_position_armed_rad_s = 0.0;
  return r;
}

}  // namespace

VehicleConfig x500_vehicle_config() {
  VehicleConfig c;
  c.name = "x500";
  c.base.mass_kg = 2.0;
  c.base.inertia_kgm2 = {0.02166666666666667, 0.02166666666666667, 0.04};
  c.base.linear_drag_N_s_m = {0.0, 0.0, 0.0};  // the gz x500 has none; rotor drag acts while they spin

  c.rotors[0] = x500_rotor(+kArm_m, -kArm_m, Turning::Ccw);  // front-right
  c.rotors[1] = x500_rotor(-kArm_m, +kArm_m, Turning::Ccw);  // back-left
  c.rotors[2] = x500_rotor(+kArm_m, +kArm_m, Turning::Cw);   // front-left
  c.rotors[3] = x500_rotor(-kArm_m, -kArm_m, Turning::Cw);   // back-right

  // Skid ends: skids 0.25 m long along x at y = +-0.132, centre z = -0.2195, 0.015 m thick.
  constexpr double skid_half_length_m = 0.125;
  constexpr double skid_y_m = 0.132;
  constexpr double skid_bottom_z_m = -0.2195 - 0.0075;
  c.landing_gear.contact_points_FLU_m = {
      Eigen::Vector3d{+skid_half_length_m, +skid_y_m, skid_bottom_z_m},
      Eigen::Vector3d{-skid_half_length_m, +skid_y_m, skid_bottom_z_m},
      Eigen::Vector3d{+skid_half_length_m, -skid_y_m, skid_bottom_z_m},
      Eigen::Vector3d{-skid_half_length_m, -skid_y_m, skid_bottom_z_m},
  };
  // Legs: stop a touchdown over tens of milliseconds, as the x500's carbon legs and skids do (0.7 m/s:
  // ~5 g peak over ~25 ms, docs/engine.md), sink 5 mm under the static load, and throw nothing back
  // up (damping ratio ~0.65 per leg, ramped in over the first 5 mm of compression).
  c.landing_gear.stiffness_N_m = 1.0e3;
  c.landing_gear.damping_N_s_m = 30.0;
  c.landing_gear.damping_depth_m = 0.005;
  // Frame points: the motor tops (the frame's other extremes); stiff, so that the vehicle rests on
  // its back or side without sinking, even with the rotors pushing it into the ground.
  constexpr double motor_top_z_m = kRotorHeight_m + 0.02;
  c.landing_gear.frame_points_FLU_m = {
      Eigen::Vector3d{+kArm_m, -kArm_m, motor_top_z_m},
      Eigen::Vector3d{-kArm_m, +kArm_m, motor_top_z_m},
      Eigen::Vector3d{+kArm_m, +kArm_m, motor_top_z_m},
      Eigen::Vector3d{-kArm_m, -kArm_m, motor_top_z_m},
  };
  c.landing_gear.frame_stiffness_N_m = 1.0e4;  // simbody-facts.md: stable at 4 ms
  c.landing_gear.frame_damping_N_s_m = 100.0;
  c.landing_gear.friction_coefficient = 0.8;
  c.landing_gear.tangential_stiffness_N_m = 4.0e3;  // stable at 4 ms up to ~7e3 (roll coupling through the skids)
  c.landing_gear.tangential_damping_N_s_m = 3.0;

  // Gazebo-classic iris / ADIS16448-class IMU (x500.md).
  c.sensors.imu.rate_hz = 250.0;
  c.sensors.imu.position_FLU_m = {0.0, 0.0, 0.0};
  // The VOXL2's ICM-42688-class IMU as PX4 configures it: +-16 g, +-2000 deg/s.
  c.sensors.imu.accel_range_m_s2 = 16.0 * 9.80665;
  c.sensors.imu.gyro_range_rad_s = 2000.0 * M_PI / 180.0;
  c.sensors.imu.gyro = {0.0003394, 3.8785e-05, 1000.0, 0.0087};
  c.sensors.imu.accel = {0.004, 0.006, 300.0, 0.196};
  // The rotors' vibration (docs/engine.md "Airframe vibration"). No published amplitude for this
  // airframe was found; PX4's log-analysis guide (docs/en/log/flight_log_analysis.md) calls a raw
  // acceleration of more than 2-3 m/s^2 peak to peak strong vibration. Sized so that at the hover
  // (~770 rad/s, 122.5 Hz) each rotor reads ~0.1 m/s^2 in the 250 Hz output, in the rotor plane at
  // its frequency and along z at its 2-blade pass (245 Hz, read at 5 Hz), so the four together stay
  // below ~1 m/s^2 peak to peak on each axis, noise included: a third of that threshold.
  c.sensors.imu.vibration.imbalance_m_s2_per_rad2_s2 = 2.5e-7;
  c.sensors.imu.vibration.blade_pass_m_s2_per_rad2_s2 = 8e-6;
  c.sensors.imu.vibration.gyro_imbalance_rad_s_per_rad2_s2 = 2.5e-9;
  c.sensors.imu.vibration.blades = 2;
  c.sensors.mag.rate_hz = 50.0;
  c.sensors.mag.noise = {0.0004, 6.4e-06, 600.0, 0.0};
  c.sensors.baro.rate_hz = 10.0;
  c.sensors.baro.noise_pa = 2.0;  // a few Pa, as real barometers; PX4 needs visible noise
  c.sensors.baro.drift_pa_sqrt_s = 0.0;
  c.sensors.baro.temperature_noise_c = 0.01;
  c.sensors.gps.rate_hz = 30.0;
  c.sensors.gps.horizontal_noise_m = 0.05;
  c.sensors.gps.vertical_noise_m = 0.1;
  c.sensors.gps.horizontal_error_sigma_m = 0.5;
  // 0.3 m: with 0.8 m, PX4 SITL (GPS as its height reference) held altitude 0.4-0.9 m off in 3 of
  // 5 seeds; x500.md gives no vertical figure. Users who want worse GPS set it in --vehicle.
  c.sensors.gps.vertical_error_sigma_m = 0.3;
  c.sensors.gps.error_correlation_time_s = 60.0;
  c.sensors.gps.velocity_noise_m_s = 0.1;
  c.sensors.gps.eph_m = 0.9;
  c.sensors.gps.epv_m = 1.2;
  c.sensors.gps.satellites = 10;
  c.sensors.gps.delay_s = 0.0;
  return c;
}

WorldConfig default_world_config() {
  WorldConfig w;
  w.gravity_m_s2 = 9.80665;
  w.home = {47.397742, 8.545594, 488.0};  // PX4 SITL default home
  // PX4's own WMM-2020 tables (src/lib/world_magnetic_model/geo_magnetic_tables.hpp, epoch
  // 2023.6), interpolated bilinearly at home as PX4 does: what EKF2 will expect there.
  w.magnetic_field = {3.2737, 63.1442, 0.48197};
  w.atmosphere = {101325.0, 15.0};
  w.wind.velocity_ENU_m_s = {0.0, 0.0, 0.0};
  w.wind.gust_sigma_m_s = {0.0, 0.0, 0.0};
  w.wind.gust_correlation_time_s = 2.0;
  w.physics = {0.004, 0.004, 300.0, 200.0};
  return w;
}

double hover_command(const VehicleConfig& vehicle, const WorldConfig& world) {
  const RotorConfig& r = vehicle.rotors[0];
  const double omega_rad_s = std::sqrt(total_mass_kg(vehicle) * world.gravity_m_s2 / (4.0 * r.motor_constant_N_s2));
  return (omega_rad_s - r.zero_position_armed_rad_s) / r.input_scaling_rad_s - r.input_offset;
}

double total_mass_kg(const VehicleConfig& config) {
  double m = config.base.mass_kg;
  for (const RotorConfig& r : config.rotors) m += r.mass_kg;
  return m;
}

VehicleConfig with_noise_disabled(VehicleConfig c) {
  for (InertialNoiseConfig* n : {&c.sensors.imu.gyro, &c.sensors.imu.accel, &c.sensors.mag.noise}) {
    n->noise_density = n->random_walk = n->turn_on_bias_sigma = 0.0;  // correlation times stay valid
    n->bias_instability = n->scale_error_sigma = n->cross_axis_sigma = 0.0;
  }
  c.sensors.imu.accel_resolution_m_s2 = c.sensors.imu.gyro_resolution_rad_s = 0.0;  // exact values
  c.sensors.imu.vibration = VibrationConfig{};
  c.sensors.mag.resolution_gauss = 0.0;  // exact values
  c.sensors.baro.noise_pa = 0.0;
  c.sensors.baro.drift_pa_sqrt_s = 0.0;
  c.sensors.baro.temperature_noise_c = 0.0;
  GpsConfig& g = c.sensors.gps;
  g.horizontal_noise_m = g.vertical_noise_m = 0.0;
  g.horizontal_error_sigma_m = g.vertical_error_sigma_m = 0.0;
  g.velocity_noise_m_s = 0.0;
  return c;
}

}  // namespace hitl::model
