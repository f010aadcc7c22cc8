// The Simbody x500: frame and four rotor bodies on pin joints, Gazebo's motor model, a spring-damper
// landing gear with stick-slip friction, gravity, wind and linear drag. One step() advances one
// fixed outer step (4 ms by default) with a fixed-step semi-explicit Euler integrator.
//
// Inputs set between steps (set_motor_commands, set_external_force_ENU_N) act in the next step.
// No Simbody type appears here: the model lives behind a pimpl (multicopter.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "base/common/expected.h"
#include "engine/model/vehicle_config.h"
#include "engine/model/vehicle_state.h"
#include "engine/model/world_config.h"

namespace hitl::model {

/// Normalized motor commands, PX4 motor order (0 front-right CCW, 1 back-left CCW, 2 front-left CW,
/// 3 back-right CW). omega_ref = (u + input_offset) * input_scaling + zero_position_armed while
/// armed, 0 while disarmed.
struct MotorCommands {
  std::array<double, 4> u{};  ///< 0..1
  bool armed = false;
};

/// One motor command made usable, the rule written once (the model and engine/hil's ActuatorInput
/// both apply it): NaN/inf become 0 (NonFinite), values outside 0..1 are clamped (OutOfRange).
enum class CommandFix { None, NonFinite, OutOfRange };
struct CheckedCommand {
  double u = 0.0;  ///< 0..1
  CommandFix fix = CommandFix::None;
};
CheckedCommand check_motor_command(double u);

/// What the engine did to bad inputs (it clamps, counts and carries on; it never prints).
struct InputCounters {
  std::uint64_t non_finite = 0;    ///< NaN/inf commands, treated as 0
  std::uint64_t out_of_range = 0;  ///< commands outside 0..1, clamped
};

/// Where to put the vehicle on reset.
struct InitialCondition {
  Eigen::Vector3d p_ENU_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_FLU_to_ENU = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_ENU_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d w_FLU_rad_s = Eigen::Vector3d::Zero();
  std::array<double, 4> rotor_speed_rad_s{};  ///< spin rate magnitudes (e.g. start hovering)
};

class Multicopter {
 public:
  /// Builds the model; the config is validated first. `seed` drives the wind gusts.
  static Expected<std::unique_ptr<Multicopter>> create(const VehicleConfig& vehicle, const WorldConfig& world,
                                                       std::uint64_t seed);
  ~Multicopter();
  Multicopter(const Multicopter&) = delete;
  Multicopter& operator=(const Multicopter&) = delete;

  /// Commands for the following step() calls. Non-finite values count and become 0; values outside
  /// 0..1 count and are clamped.
  void set_motor_commands(const MotorCommands& commands);
  /// Motor i's effectiveness: its rotor's thrust, drag and torques on the frame x k from the next
  /// step (a motor fault; 1 = healthy, 0 = out). Kept across reset(); a non-finite or negative k is 0.
  void set_motor_effectiveness(std::size_t i, double k);
  /// A wind event (faults: wind, gust, turbulence) on top of the world's wind, until changed
  /// (model/wind.h); kept across reset().
  void set_wind_event(const Eigen::Vector3d& extra_ENU_m_s, double turbulence_sigma_m_s, double turbulence_tau_s);
  /// An extra force on the base origin (tests: side load; a UI "push"), world ENU, until changed.
  void set_external_force_ENU_N(const Eigen::Vector3d& f_ENU_N);

  /// Advances one outer step. On an integration blow-up (non-finite state, speed or angular rate
  /// beyond the limits of WorldConfig::physics) returns an error naming the step and the state; the
  /// state() then stays at the last good step and every later step() returns the same error until
  /// reset().
  Status step();

  /// Back to home at rest on the landing gear, motors stopped, time 0 (the gust process restarts
  /// from its seed too, so a reset run repeats the first).
  void reset();
  /// Back to time 0 at a given pose, velocity and rotor speeds (e.g. a drop from altitude).
  /// Commands go back to zero, disarmed.
  void reset(const InitialCondition& initial);

  const VehicleState& state() const;
  const InputCounters& input_counters() const;
  const VehicleConfig& vehicle_config() const;
  const WorldConfig& world_config() const;
  /// The pose in which the vehicle rests on its landing gear at home (ENU z of the base origin).
  InitialCondition resting_on_ground() const;

 private:
  struct Impl;
  explicit Multicopter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hitl::model
