// The spec's trajectory_rc automation: INIT -> ARM -> TAKEOFF -> TRAJECTORY -> HOLD -> LAND ->
// DISARM -> DONE. It arms, takes off to the first waypoint's height, switches to a manual mode and
// flies the trajectory by stick (RC_CHANNELS_OVERRIDE, PX4's default channel map), holds, lands
// and waits for the disarm. Its commands are the action API's requests (action.h). Two stick modes:
//   Velocity (Position mode, POSCTL): a P-controller from position error to velocity sticks.
//   Attitude (Stabilized): the pilot closes position and velocity itself: position error -> velocity
//     -> acceleration -> tilt sticks (stick = tilt / MPC_MAN_TILT_MAX) and a thrust stick through
//     the inverse of PX4's hover-rescaled throttle curve, with an integrator for the hover thrust.
// Pure logic: the caller gives it time, the vehicle's pose and the board's frames, and sends the
// messages it returns.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/mavlink/frame.h"
#include "base/mavlink/messages.h"
#include "engine/vehicle/action.h"
#include "engine/vehicle/command_request.h"
#include "engine/vehicle/trajectory.h"

namespace hitl::vehicle {

enum class PilotState { Init, Arm, Takeoff, Trajectory, Hold, Land, Disarm, Done, Failed };
const char* to_string(PilotState state);

enum class StickMode { Velocity, Attitude };
const char* to_string(StickMode mode);  ///< "velocity", "attitude"

struct PilotConfig {
  double rc_rate_hz = 20;               ///< RC_CHANNELS_OVERRIDE rate (PX4 loses RC after COM_RC_LOSS_T 0.5 s)
  double kp_1_s = 1.0;                  ///< velocity command per metre of position error
  double max_xy_m_s = 10.0;             ///< full stick: PX4 MPC_VEL_MANUAL
  double max_up_m_s = 3.0;              ///< MPC_Z_VEL_MAX_UP
  double max_down_m_s = 1.5;            ///< MPC_Z_VEL_MAX_DN
  double max_yaw_rate_rad_s = 2.618;    ///< MPC_MAN_Y_MAX 150 deg/s
  double kp_yaw_1_s = 1.5;
  double stick_deadzone = 0.1;          ///< PX4 MPC_HOLD_DZ: the pilot deflects past it to ask for small speeds
  StickMode mode = StickMode::Velocity;
  // Attitude mode: the board's Stabilized stick scaling (read from its parameters when possible).
  double max_tilt_rad = 0.6109;         ///< MPC_MAN_TILT_MAX 35 deg: full roll/pitch stick
  double thr_hover = 0.59;              ///< MPC_THR_HOVER: mid throttle stick
  double thr_min = 0.08;                ///< MPC_MANTHR_MIN: zero throttle stick
  double thr_max = 1.0;                 ///< MPC_THR_MAX: full throttle stick
  double kv_xy_1_s = 1.8;               ///< acceleration per m/s of horizontal velocity error
  double kv_z_1_s = 3.0;                ///< acceleration per m/s of vertical velocity error
  double ki_z_1_s2 = 1.0;               ///< hover-thrust integrator, per m/s of vertical error per s
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
  std::array<double, 3> v_ENU_m_s{};  ///< used by the attitude mode
  double yaw_ENU_rad = 0;
};

/// The throttle stick that gives `thrust` in Stabilized: the inverse of PX4's hover-rescaled
/// throttle curve with the config's MPC_THR_HOVER / MPC_MANTHR_MIN / MPC_THR_MAX.
double throttle_for_thrust(double thrust, const PilotConfig& config);

/// RC_CHANNELS_OVERRIDE's sticks (PX4's default map: 1 roll, 2 pitch, 3 throttle, 4 yaw) as
/// MANUAL_CONTROL (x forward, y right, z thrust 0..1000, r clockwise).
mavlink::msg::ManualControl manual_control_for(const mavlink::msg::RcChannelsOverride& rc);

struct PilotOutput {
  std::vector<mavlink::msg::CommandLong> commands;
  std::optional<mavlink::msg::RcChannelsOverride> rc;
  /// The same sticks as MANUAL_CONTROL (PX4's joystick input): PX4 SITL takes only that
  /// (COM_RC_IN_MODE 1), a board usually RC; PX4 uses whichever its COM_RC_IN_MODE allows.
  std::optional<mavlink::msg::ManualControl> manual;
  std::optional<std::string> event;  ///< a state change, in words
  /// TRAJECTORY and HOLD: the reference flown this step (ENU from the start; TrajectoryFlight
  /// gives it in the pose's own frame); in TRAJECTORY also the error scored into tracking().
  std::optional<TrajectoryReference> reference;
  std::optional<double> tracking_error_m;
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
  /// Another view of where the vehicle is (the simulator's ground truth, same origin convention),
  /// scored against the reference while the trajectory is flown; see truth_tracking().
  void observe_truth(double t_s, const PilotPose& truth);

  PilotState state() const { return state_; }
  const std::string& failure() const { return failure_; }
  TrackingStats tracking() const { return tracking_.stats(); }
  TrackingStats truth_tracking() const { return truth_tracking_.stats(); }
  bool finished() const { return state_ == PilotState::Done || state_ == PilotState::Failed; }

 private:
  void enter(PilotState next, double t_s, PilotOutput& out, const std::string& why = "");
  mavlink::msg::CommandLong command(const CommandRequest& request) const;
  /// The RC rate's next sticks are due at `t_s`.
  bool sticks_due(double t_s) const { return t_s - last_rc_s_ >= 1.0 / config_.rc_rate_hz; }
  /// `rc` as this step's sticks: RC_CHANNELS_OVERRIDE and MANUAL_CONTROL, remembered for LAND.
  void send_sticks(double t_s, const mavlink::msg::RcChannelsOverride& rc, PilotOutput& out);
  /// The mode the sticks are for: Position (velocity sticks) or Stabilized (attitude sticks).
  Px4Mode stick_mode() const { return config_.mode == StickMode::Attitude ? kPx4Stabilized : kPx4Position; }
  mavlink::msg::RcChannelsOverride sticks(double roll, double pitch, double yaw, double throttle) const;
  mavlink::msg::RcChannelsOverride velocity_sticks(const TrajectoryReference& ref, const PilotPose& pose) const;
  /// Sends the sticks that fly towards `ref` in the pilot's stick mode (its dt from the last sticks).
  void fly_sticks_to(const TrajectoryReference& ref, const PilotPose& pose, double t_s, PilotOutput& out);
  mavlink::msg::RcChannelsOverride attitude_sticks(const TrajectoryReference& ref, const PilotPose& pose, double dt_s);
  bool flying_reference() const { return state_ == PilotState::Trajectory || state_ == PilotState::Hold; }

  /// Sum of squares and maximum of position error.
  class ErrorStats {
   public:
    void add(double err_m);
    TrackingStats stats() const;
   private:
    double sum_sq_ = 0;
    double max_ = 0;
    uint64_t n_ = 0;
  };

  Trajectory trajectory_;
  PilotConfig config_;
  PilotState state_ = PilotState::Init;
  double state_start_s_ = 0;
  double last_command_s_ = -1e9;
  double last_rc_s_ = -1e9;
  double centred_since_s_ = -1;  ///< TAKEOFF at height: the first centred sticks sent
  std::optional<mavlink::msg::RcChannelsOverride> last_sticks_;  ///< the last sticks sent (LAND holds them)
  static constexpr double kCentredBeforeMode_s = 1.0;
  double trajectory_start_s_ = 0;
  bool armed_ = false;
  bool ready_ = false;
  bool mode_set_ = false;  ///< the board's HEARTBEAT shows the mode the sticks are for
  bool takeoff_mode_seen_ = false;  ///< the board's HEARTBEAT has shown AUTO.TAKEOFF
  bool takeoff_ended_ = false;      ///< ... and then Hold, armed: the board ended its takeoff
  std::optional<double> short_by_m_;  ///< how far short of the height the board ended it (the sticks climb the rest)
  std::optional<uint8_t> takeoff_ack_;
  std::string failure_;
  ErrorStats tracking_;
  ErrorStats truth_tracking_;
  double hover_integral_ = 0;  ///< attitude mode: thrust ratio correction learned in flight
  double last_rc_t_s_ = -1;
};

}  // namespace hitl::vehicle
