// The spec's trajectory_rc automation: INIT -> ARM -> TAKEOFF -> TRAJECTORY -> HOLD -> LAND ->
// DISARM -> DONE. It arms, takes off to the first waypoint's height, switches to Position mode and
// flies the trajectory with a P-controller from position error to sticks (sent as
// RC_CHANNELS_OVERRIDE, PX4's default channel map), holds, lands and waits for the disarm.
// Pure logic: the caller gives it time, the vehicle's pose and the board's frames, and sends the
// messages it returns.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/mavlink/frame.h"
#include "engine/mavlink/messages.h"
#include "engine/vehicle/trajectory.h"

namespace hitl::vehicle {

enum class PilotState { Init, Arm, Takeoff, Trajectory, Hold, Land, Disarm, Done, Failed };
const char* to_string(PilotState state);

struct PilotConfig {
  double rc_rate_hz = 20;               ///< RC_CHANNELS_OVERRIDE rate (PX4 loses RC after COM_RC_LOSS_T 0.5 s)
  double kp_1_s = 1.0;                  ///< velocity command per metre of position error
  double max_xy_m_s = 10.0;             ///< full stick: PX4 MPC_VEL_MANUAL
  double max_up_m_s = 3.0;              ///< MPC_Z_VEL_MAX_UP
  double max_down_m_s = 1.5;            ///< MPC_Z_VEL_MAX_DN
  double max_yaw_rate_rad_s = 2.618;    ///< MPC_MAN_Y_MAX 150 deg/s
  double kp_yaw_1_s = 1.5;
  double stick_deadzone = 0.1;          ///< PX4 MPC_HOLD_DZ: the pilot deflects past it to ask for small speeds
  double hold_s = 5.0;                  ///< HOLD after the last waypoint
  double takeoff_tolerance_m = 0.3;
  double home_alt_msl_m = 488.0;        ///< for NAV_TAKEOFF's AMSL altitude
  double state_timeout_s = 60.0;        ///< any state but TRAJECTORY longer than this fails
  uint8_t target_system = 1;
  uint8_t target_component = 1;
};

/// Where the vehicle is: ENU metres relative to where it rested at the start, yaw ENU.
struct PilotPose {
  std::array<double, 3> p_ENU_m{};
  double yaw_ENU_rad = 0;
};

struct PilotOutput {
  std::vector<mavlink::msg::CommandLong> commands;
  std::optional<mavlink::msg::RcChannelsOverride> rc;
  std::optional<std::string> event;  ///< a state change, in words
};

struct TrackingStats {
  uint64_t samples = 0;
  double rms_m = 0;
  double max_m = 0;
};

class TrajectoryPilot {
 public:
  TrajectoryPilot(Trajectory trajectory, PilotConfig config);

  /// HEARTBEAT (armed), SYS_STATUS (ready to arm), COMMAND_ACK, from the board.
  void on_board_frame(const mavlink::Frame& frame);
  PilotOutput step(double t_s, const PilotPose& pose);

  PilotState state() const { return state_; }
  const std::string& failure() const { return failure_; }
  TrackingStats tracking() const;
  bool finished() const { return state_ == PilotState::Done || state_ == PilotState::Failed; }

 private:
  void enter(PilotState next, double t_s, PilotOutput& out, const std::string& why = "");
  mavlink::msg::CommandLong command(uint16_t id, std::array<float, 7> params) const;
  mavlink::msg::RcChannelsOverride sticks(double roll, double pitch, double yaw, double throttle) const;

  Trajectory trajectory_;
  PilotConfig config_;
  PilotState state_ = PilotState::Init;
  double state_start_s_ = 0;
  double last_command_s_ = -1e9;
  double last_rc_s_ = -1e9;
  double trajectory_start_s_ = 0;
  bool armed_ = false;
  bool ready_ = false;
  bool mode_set_ = false;
  std::optional<uint8_t> takeoff_ack_;
  std::string failure_;
  double sum_sq_ = 0;
  double max_err_ = 0;
  uint64_t samples_ = 0;
};

}  // namespace hitl::vehicle
