// The emulated board's flight stack seen from the MAVLink side: sensor samples in (as dsp_hitl
// publishes them), commands and sticks in, motor commands and state out. Wraps the flight core
// (emulator/flight) and exposes its gains as PX4 parameters.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/mavlink/enums.h"
#include "emulator/flight/status_message.h"
#include "emulator/param_store.h"
#include "target/core/px4_topics.h"

namespace hitl::target {

/// What the MAVLink side reports, in the wire's frames (NED, FRD).
struct FlightState {
  bool armed = false;
  uint32_t custom_mode = 0;    ///< PX4's main/sub mode word
  uint8_t base_mode = 0;       ///< MAV_MODE_FLAG bits without HIL (the board adds it with SYS_HITL)
  std::string mode_name;       ///< "Position", "Hold", "Takeoff", "Land"
  mavlink::MavLandedState landed = mavlink::MavLandedState::OnGround;
  bool ready_to_arm = false;
  std::string not_ready_reason;  ///< "Preflight Fail: ..." when not ready
  // estimate
  bool attitude_valid = false, local_valid = false, global_valid = false, home_set = false;
  std::array<double, 4> q_FRD_to_NED{1, 0, 0, 0};  ///< w, x, y, z
  double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
  std::array<double, 3> w_FRD_rad_s{};
  std::array<double, 3> p_NED_m{}, v_NED_m_s{};
  double lat_deg = 0, lon_deg = 0, alt_msl_m = 0;
  double home_lat_deg = 0, home_lon_deg = 0, home_alt_msl_m = 0;
  // ESTIMATOR_STATUS
  uint16_t estimator_flags = 0;
  double vel_ratio = 0, pos_horiz_ratio = 0, pos_vert_ratio = 0, mag_ratio = 0;
  double pos_horiz_accuracy_m = 0, pos_vert_accuracy_m = 0;
  std::array<double, 4> motor_commands{};
};

struct CommandResult {
  mavlink::MavResult result = mavlink::MavResult::Accepted;
  std::string text;  ///< a STATUSTEXT to send with it (a denial says why), may be empty
};

class FlightAdapter {
 public:
  /// Registers the flight core's parameters (PX4 names, defaults, ranges) in `params`.
  explicit FlightAdapter(ParamStore& params);
  ~FlightAdapter();

  void on_imu(const SensorAccel& accel, const SensorGyro& gyro);
  void on_mag(const SensorMag& mag);
  void on_baro(const SensorBaro& baro);
  void on_gps(const SensorGps& gps);
  /// RC_CHANNELS_OVERRIDE chan1..8 in us (PX4's default map; 0 and UINT16_MAX keep a channel as it was).
  void on_rc_override(const std::array<uint16_t, 8>& channels_us, uint64_t now_us);
  /// MANUAL_CONTROL, PX4-normalised: roll, pitch (+ forward), yaw (+ clockwise) -1..1, throttle 0..1.
  void on_sticks(double roll, double pitch, double yaw, double throttle, uint64_t now_us);

  /// Refused unless forced while the preflight checks fail (calibration first, then the estimator's).
  CommandResult arm(bool force, uint64_t now_us);
  CommandResult disarm(bool force, uint64_t now_us);
  CommandResult takeoff(double altitude_amsl_m, uint64_t now_us);  ///< NaN: MIS_TAKEOFF_ALT above home
  CommandResult land(uint64_t now_us);
  /// MAV_CMD_DO_SET_MODE: PX4's main and sub mode.
  CommandResult set_mode(uint8_t main_mode, uint8_t sub_mode, uint64_t now_us);

  /// Runs estimator and controllers up to `now_us`; returns motor commands 0..1 (PX4 motor order).
  std::array<double, 4> step(uint64_t now_us);

  FlightState state() const;
  /// Messages the flight stack wants to tell the operator (mode changes, landing, auto-disarm, and
  /// every denial a command reply carries), each once, with its severity.
  std::vector<flight::StatusMessage> take_messages();
  std::string commander_status() const;
  /// `commander check`: "Preflight check: OK", or each failure and "Preflight check: FAILED".
  std::string commander_check() const;
  /// Fault injection (hitl target --fault ekf-not-converging, faults.h): every magnetometer sample
  /// turned by `angle_rad` about body down, alternately one way and the other.
  void inject_mag_swing(double angle_rad) { mag_swing_rad_ = angle_rad; }
  std::string ekf2_status() const;

 private:
  /// PX4's calibration check: CAL_ACC0_ID / CAL_GYRO0_ID / CAL_MAG0_ID must be dsp_hitl's device
  /// IDs, else that sensor is uncalibrated ("Preflight Fail: Accel 0 uncalibrated"); empty when fine.
  std::string calibration_failure() const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  const ParamStore& params_;
  double mag_swing_rad_ = 0;
  bool mag_swing_right_ = false;
};

}  // namespace hitl::target
