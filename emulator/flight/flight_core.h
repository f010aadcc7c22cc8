// The emulated board's flight stack, without networking or MAVLink: commander (arming, modes,
// takeoff, land, auto-disarm), estimator, PX4's controller cascade and the x500 allocation.
//
// Each tick the emulator: hands over the sensor samples that arrived (handle_imu / handle_mag /
// handle_baro / handle_gps, handle_sticks for RC_CHANNELS_OVERRIDE), calls step(now_us) once, and
// sends actuators() as HIL_ACTUATOR_CONTROLS. Commands (arm, disarm, takeoff, land, set_mode)
// return a reply with a PX4-like reason; take_messages() drains the STATUSTEXT-worthy events.
// Deterministic: time only from the caller, no threads, no clocks.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "base/common/severity.h"
#include "base/contract/hil_actuators.h"
#include "emulator/flight/estimator.h"
#include "emulator/flight/flight_params.h"
#include "emulator/flight/inputs.h"
#include "emulator/flight/land_detector.h"
#include "emulator/flight/manual_attitude.h"
#include "emulator/flight/manual_setpoint.h"
#include "emulator/flight/mixer.h"
#include "emulator/flight/position_control.h"
#include "emulator/flight/px4_modes.h"
#include "emulator/flight/rate_control.h"
#include "emulator/flight/status_message.h"

namespace hitl::flight {

/// Outcome of a command, mapped by the emulator to MAV_RESULT (Accepted 0, TemporarilyRejected 1,
/// Denied 2, Failed 4).
enum class CommandResult { Accepted, TemporarilyRejected, Denied, Failed };
std::string to_string(CommandResult result);

struct CommandReply {
  CommandResult result = CommandResult::Accepted;
  std::string reason;  ///< empty when accepted
};

/// HIL_ACTUATOR_CONTROLS content.
struct ActuatorOutput {
  std::uint64_t time_us = 0;
  std::array<double, 4> u{};  ///< controls[0..3], 0..1, PX4 motor order
  bool armed = false;
  std::uint8_t mode = 0;      ///< MAV_MODE_FLAG (SAFETY_ARMED 128 when armed)
  std::uint64_t flags = kVoxl2ActuatorFlags;  ///< as the VOXL2 sends for a quad (base/contract/hil_actuators.h)
};

struct Home {
  bool valid = false;
  Eigen::Vector3d p_NED_m = Eigen::Vector3d::Zero();
  double lat_deg = 0.0, lon_deg = 0.0, alt_msl_m = 0.0;
  double yaw_rad = 0.0;
};

/// What the controllers were asked and produced in the last step.
struct ControlSnapshot {
  PositionSetpoint position;
  PositionControlOutput position_out;
  Eigen::Vector3d rate_sp_FRD_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque_FRD = Eigen::Vector3d::Zero();  ///< normalized
  std::array<double, 4> motor_thrust{};
  bool ground_contact = false;
};

class FlightCore {
 public:
  explicit FlightCore(const FlightParams& params = {});
  FlightCore(const FlightCore&) = delete;
  FlightCore& operator=(const FlightCore&) = delete;

  /// The live parameters: set_param(core.params(), name, value) takes effect at the next sample.
  FlightParams& params() { return params_; }
  const FlightParams& params() const { return params_; }

  void handle_imu(const ImuSample& sample) { estimator_.handle_imu(sample); }
  void handle_mag(const MagSample& sample) { estimator_.handle_mag(sample); }
  void handle_baro(const BaroSample& sample) { estimator_.handle_baro(sample); }
  void handle_gps(const GpsSample& sample) { estimator_.handle_gps(sample); }
  void handle_sticks(const StickInput& sticks);

  /// MAV_CMD_COMPONENT_ARM_DISARM. Arming needs the preflight checks unless forced (param2 21196).
  CommandReply arm(bool force = false);
  /// Disarming in the air is denied unless forced.
  CommandReply disarm(bool force = false);
  /// MAV_CMD_NAV_TAKEOFF: needs armed (PX4 would arm-and-go only via its mission logic).
  CommandReply takeoff(const TakeoffRequest& request = {});
  /// MAV_CMD_NAV_LAND.
  CommandReply land();
  /// MAV_CMD_DO_SET_MODE / SET_MODE (see flight_mode_from_px4).
  CommandReply set_mode(FlightMode mode);

  /// Runs commander, setpoints, controllers and allocation for the time now_us (call at 200-250 Hz).
  void step(std::uint64_t now_us);

  const ActuatorOutput& actuators() const { return actuators_; }
  const Estimate& estimate() const { return estimator_.estimate(); }
  EstimatorStatus estimator_status() const { return estimator_.status(); }
  Readiness preflight_check() const { return estimator_.preflight_check(); }
  bool armed() const { return armed_; }
  FlightMode mode() const { return mode_; }
  LandedState landed_state() const { return landed_state_; }
  std::uint32_t custom_mode() const { return px4_custom_mode(mode_); }
  std::uint8_t base_mode() const { return mav_base_mode(mode_, armed_); }
  const Home& home() const { return home_; }
  const ControlSnapshot& control() const { return control_; }

  /// STATUSTEXT-worthy events since the last call (arming, denials, takeoff, landing, disarm).
  std::vector<StatusMessage> take_messages();
  /// `commander status` / `ekf2 status` lines for the board's shell.
  std::vector<std::string> commander_status_lines() const;
  std::vector<std::string> ekf2_status_lines() const { return estimator_.status_lines(); }

 private:
  void say(Severity sev, std::string text);
  void do_disarm(const char* why);
  void set_home();
  void enter_mode(FlightMode mode);
  void reset_controllers();
  bool sticks_fresh() const;
  StickInput current_sticks() const;
  bool sticks_deflected_for_override() const;
  PositionSetpoint setpoint_for_mode(double dt_s);
  void run_controllers(const PositionSetpoint& sp, double dt_s);
  void run_attitude_rate(const PositionControlOutput& pos, double yawspeed_rad_s, double dt_s);
  void idle_outputs();

  FlightParams params_;
  Estimator estimator_;
  std::optional<Mixer> mixer_;
  PositionControl position_control_;
  RateControl rate_control_;
  LandDetector land_detector_;
  ManualPositionSetpoint manual_;
  ManualAttitudeSetpoint manual_attitude_;

  std::uint64_t now_us_ = 0;
  bool stepped_ = false;
  bool armed_ = false;
  FlightMode mode_ = FlightMode::Hold;
  LandedState landed_state_ = LandedState::OnGround;
  bool flown_since_arming_ = false;
  std::uint64_t on_ground_since_us_ = 0;
  Home home_;

  StickInput sticks_;
  bool sticks_seen_ = false;

  // Mode state
  Eigen::Vector3d hold_NED_m_ = Eigen::Vector3d::Zero();
  double yaw_sp_rad_ = 0.0;
  Eigen::Vector2d takeoff_xy_NED_m_ = Eigen::Vector2d::Zero();
  double takeoff_start_z_m_ = 0.0;
  double takeoff_target_z_m_ = 0.0;
  double takeoff_ramp_z_m_ = 0.0;
  double thrust_limit_ = kNaN;  ///< landing: ramps down after ground contact

  Eigen::Vector3d last_rate_FRD_rad_s_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_accel_FRD_rad_s2_ = Eigen::Vector3d::Zero();
  MixerOutput last_mix_;

  ActuatorOutput actuators_;
  ControlSnapshot control_;
  std::vector<StatusMessage> messages_;
};

}  // namespace hitl::flight
