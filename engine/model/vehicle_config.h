// What a vehicle is: bodies, rotors and motor model, landing gear, sensors and their noise.
// Plain values; the compiled-in x500 is x500_vehicle_config() (x500_defaults.cpp), the JSON file
// format is read and written by config_json.h. Body quantities are in FLU about the base origin.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

namespace hitl::model {

/// Spin direction seen from above (body +z FLU up): CCW spins about +z, CW about -z.
enum class Turning { Ccw, Cw };

/// One rotor and its motor, as Gazebo's MulticopterMotorModel describes it.
struct RotorConfig {
  Eigen::Vector3d position_FLU_m = Eigen::Vector3d::Zero();  ///< hub (rotor body origin) from base origin
  Turning turning = Turning::Ccw;
  double mass_kg = 0.0;
  Eigen::Vector3d inertia_kgm2 = Eigen::Vector3d::Zero();  ///< ixx, iyy, izz about the rotor's own axes
  double time_constant_up_s = 0.0;    ///< first-order lag of rotor speed while speeding up
  double time_constant_down_s = 0.0;  ///< ... while slowing down
  double max_rot_velocity_rad_s = 0.0;  ///< the speed reference is clamped to this
  double motor_constant_N_s2 = 0.0;     ///< kF: thrust = kF * omega^2 [N/(rad/s)^2]
  double moment_constant_m = 0.0;       ///< kM: drag torque = kM * thrust, against the spin
  double rotor_drag_coefficient = 0.0;  ///< in-plane drag = -|omega| * c * v_perp [N/((rad/s)(m/s))]
  double rolling_moment_coefficient = 0.0;  ///< rolling moment = -|omega| * c * v_perp [N m/((rad/s)(m/s))]
  double axial_speed_falloff_m_s = 0.0;     ///< thrust scaled by clamp(1 - v_axial / this, 0, 1)
  double input_offset = 0.0;                ///< omega_ref = (u + offset) * scaling + zero_position_armed
  double input_scaling_rad_s = 0.0;
  double zero_position_armed_rad_s = 0.0;
};

/// The frame (base_link) without rotors.
struct BaseConfig {
  double mass_kg = 0.0;
  Eigen::Vector3d inertia_kgm2 = Eigen::Vector3d::Zero();  ///< ixx, iyy, izz about the base origin (= its CoM)
  Eigen::Vector3d linear_drag_N_s_m = Eigen::Vector3d::Zero();  ///< F_FLU = -c (.) v_air_FLU, per body axis
};

/// Ground contact (ground_contact.h): the legs' spring-damper at each skid end, and stiffer frame
/// points (the motor tops) so that the vehicle rests on the ground at any attitude, upside down
/// included; stick-slip friction at every point (simbody-facts.md).
struct LandingGearConfig {
  std::array<Eigen::Vector3d, 4> contact_points_FLU_m{};  ///< skid ends: the legs
  double stiffness_N_m = 0.0;             ///< legs: normal, per contact point
  double damping_N_s_m = 0.0;             ///< legs: normal, per contact point
  /// The damping grows linearly with the compression up to this depth (then holds): a leg touching
  /// down does not jerk (no force step at first contact), as a real leg's flex and foam do.
  double damping_depth_m = 0.0;
  std::array<Eigen::Vector3d, 4> frame_points_FLU_m{};  ///< the frame's other extremes (motor tops)
  double frame_stiffness_N_m = 0.0;       ///< frame points: normal, per point
  double frame_damping_N_s_m = 0.0;       ///< frame points: normal, per point
  double friction_coefficient = 0.0;      ///< mu: tangential force capped at mu * normal force
  double tangential_stiffness_N_m = 0.0;  ///< spring to the stick anchor, per contact point
  double tangential_damping_N_s_m = 0.0;
};

/// A three-axis inertial-type noise: white noise + Gauss-Markov bias random walk + turn-on bias
/// (the Gazebo IMU plugin's model), a flicker-like bias instability, and a scale and cross-axis
/// error drawn at start. Units per sensor: gyro rad/s, accel m/s^2, mag gauss.
struct InertialNoiseConfig {
  double noise_density = 0.0;            ///< white noise [unit/sqrt(Hz)]; sample sigma = density * sqrt(rate)
  double random_walk = 0.0;              ///< bias diffusion [unit/s/sqrt(Hz)]
  double bias_correlation_time_s = 0.0;  ///< bias decays with this time constant
  double turn_on_bias_sigma = 0.0;       ///< constant bias per axis drawn at start [unit]
  /// IEEE 952 bias instability B [unit]: the Allan deviation's flat floor is 0.664 B (0: none).
  double bias_instability = 0.0;
  double scale_error_sigma = 0.0;        ///< per-axis scale factor error drawn at start [fraction]
  double cross_axis_sigma = 0.0;         ///< per off-diagonal cross-axis sensitivity drawn at start [fraction]
};

/// What the rotors shake the IMU with (0: off, the default). Each rotor i at speed w_i, phase
/// phi_i = integral of w_i (its imbalance turning with it), sized as an imbalance force grows, w^2:
///   accel_FLU += imbalance w^2 (cos phi, sin phi, 0) + blade_pass w^2 (0, 0, cos(blades phi))
///   gyro_FLU  += gyro_imbalance w^2 (cos phi, sin phi, 0)
struct VibrationConfig {
  double imbalance_m_s2_per_rad2_s2 = 0.0;       ///< in the rotor plane at the rotor's frequency
  double blade_pass_m_s2_per_rad2_s2 = 0.0;      ///< along the rotor axis at blades x the rotor's frequency
  double gyro_imbalance_rad_s_per_rad2_s2 = 0.0; ///< about the in-plane axes at the rotor's frequency
  int blades = 2;
};

/// The part's own filtering before its output (off by default: the output is the mean of the signal over
/// each sample interval, as if sampled continuously): a second-order anti-alias low-pass, a first-order
/// low-pass after it (the user-interface filter of InvenSense parts), sampled at the part's output data
/// rate and averaged over each HIL interval, as PX4 integrates a part's FIFO. Applied to the airframe's
/// vibration lines (the rigid-body motion lies far below these bandwidths).
struct ImuFilterConfig {
  double output_data_rate_hz = 0.0;  ///< the part's sampling (0: a continuous mean)
  double anti_alias_hz = 0.0;        ///< 3-dB frequency of the second-order anti-alias filter (0: none)
  double ui_filter_hz = 0.0;         ///< 3-dB frequency of the first-order filter after it (0: none)
};

struct ImuConfig {
  double rate_hz = 0.0;
  Eigen::Vector3d position_FLU_m = Eigen::Vector3d::Zero();  ///< IMU mount from base origin (axes = body)
  double accel_range_m_s2 = 0.0;  ///< full scale per axis: readings saturate here (x500: +-16 g)
  double gyro_range_rad_s = 0.0;  ///< full scale per axis (x500: +-2000 deg/s)
  double accel_resolution_m_s2 = 0.0;  ///< one LSB: readings are rounded to it (0: not quantised)
  double gyro_resolution_rad_s = 0.0;  ///< one LSB (0: not quantised)
  InertialNoiseConfig gyro;   ///< rad/s
  InertialNoiseConfig accel;  ///< m/s^2
  VibrationConfig vibration;  ///< the airframe's, from the rotors (the x500's: x500_defaults.cpp)
  ImuFilterConfig filter;     ///< the part's filter and sampling (the generic IMU: none)
};

struct MagConfig {
  double rate_hz = 0.0;
  InertialNoiseConfig noise;  ///< gauss
  double range_gauss = 0.0;       ///< full scale per axis: readings saturate here (0: no limit)
  double resolution_gauss = 0.0;  ///< one LSB: readings are rounded to it (0: not quantised)
};

struct BaroConfig {
  double rate_hz = 0.0;
  double noise_pa = 0.0;            ///< white noise sigma per sample
  double drift_pa_sqrt_s = 0.0;     ///< random-walk drift density [Pa/sqrt(s)], 0 = none
  double temperature_noise_c = 0.0; ///< white noise sigma on the temperature
};

struct GpsConfig {
  double rate_hz = 0.0;
  double horizontal_noise_m = 0.0;        ///< white noise sigma per sample, each horizontal axis
  double vertical_noise_m = 0.0;
  double horizontal_error_sigma_m = 0.0;  ///< stationary sigma of the slowly wandering position error
  double vertical_error_sigma_m = 0.0;
  double error_correlation_time_s = 0.0;  ///< time constant of that error (Gauss-Markov)
  double velocity_noise_m_s = 0.0;        ///< white noise sigma per velocity axis
  double eph_m = 0.0;                     ///< reported horizontal accuracy
  double epv_m = 0.0;                     ///< reported vertical accuracy
  /// eph/epv follow the modelled error (the receiver's own accuracy estimate moving with it) instead
  /// of the constants above: eph = k sqrt(e_E^2 + e_N^2 + 2 horizontal_noise^2), epv = k sqrt(e_U^2 +
  /// vertical_noise^2), k the gps-noise fault's scale. Off: the constants (the generic receiver).
  bool accuracy_follows_error = false;
  int satellites = 0;
  double delay_s = 0.0;                   ///< samples reported this late (0 = none)
};

struct SensorsConfig {
  ImuConfig imu;
  MagConfig mag;
  BaroConfig baro;
  GpsConfig gps;
};

struct VehicleConfig {
  std::string name;
  BaseConfig base;
  std::array<RotorConfig, 4> rotors{};  ///< PX4 motor order: 0 FR CCW, 1 BL CCW, 2 FL CW, 3 BR CW
  LandingGearConfig landing_gear;
  SensorsConfig sensors;
};

/// The same config with every sensor noise, bias and drift set to zero (exact sensor values).
/// A flight stack must not be fed this without a warning: PX4 marks repeating values stale.
VehicleConfig with_noise_disabled(VehicleConfig config);

/// Total mass of base and rotors [kg].
double total_mass_kg(const VehicleConfig& config);

}  // namespace hitl::model
