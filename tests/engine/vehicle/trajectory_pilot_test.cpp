// The trajectory_rc pilot as pure logic: its state machine against scripted board frames, the
// sticks of both modes, and the attitude mode's throttle against the flight core's throttle curve.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <optional>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "emulator/flight/manual_attitude.h"
#include "engine/vehicle/trajectory_pilot.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;

/// Frames as the board (sysid 1) would send them.
class Board {
 public:
  template <class M>
  mavlink::Frame frame(const M& m) {
    mavlink::FrameBuffer buf;
    const std::size_t n = encoder_.encode(m, buf);
    std::optional<mavlink::Frame> out;
    parser_.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) { out = f; });
    return *out;
  }
  mavlink::Frame ready() {
    msg::SysStatus s;
    s.onboard_control_sensors_health = mavlink::sys_status::kPrearmCheck;
    return frame(s);
  }
  mavlink::Frame heartbeat(bool armed, uint32_t custom_mode = 0) {
    msg::Heartbeat hb;
    hb.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Px4);
    hb.base_mode = armed ? mavlink::mode_flag::kSafetyArmed : 0;
    hb.custom_mode = custom_mode;
    return frame(hb);
  }
  mavlink::Frame ack(uint16_t command) {
    msg::CommandAck a;
    a.command = command;
    a.result = static_cast<uint8_t>(mavlink::MavResult::Accepted);
    return frame(a);
  }

 private:
  mavlink::MessageSet set_ = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser_{set_};
  mavlink::FrameEncoder encoder_{1, 1};
};

Trajectory square() {
  auto t = Trajectory::parse(R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 1.5707963},
                                              {"t": 10, "x": 0, "y": 10, "z": 2, "yaw": 1.5707963}]})",
                             "t.json");
  EXPECT_TRUE(t.ok());
  return *t;
}

/// Runs the pilot from INIT to TRAJECTORY; returns the main mode it asked for.
float fly_to_trajectory(TrajectoryPilot& pilot, Board& board, double& t_s) {
  PilotPose ground;
  ground.yaw_ENU_rad = M_PI / 2;  // facing north
  EXPECT_FALSE(pilot.step(t_s, ground).event);  // INIT waits for the board
  pilot.on_board_frame(board.ready());
  EXPECT_EQ(*pilot.step(t_s += 0.05, ground).event, "trajectory: ARM (the board is ready to arm)");
  auto arm = pilot.step(t_s += 0.05, ground);
  EXPECT_EQ(arm.commands.size(), 1u);
  EXPECT_EQ(arm.commands[0].command, mavlink::cmd::kComponentArmDisarm);
  pilot.on_board_frame(board.heartbeat(true));
  pilot.step(t_s += 0.05, ground);
  EXPECT_EQ(pilot.state(), PilotState::Takeoff);
  auto takeoff = pilot.step(t_s += 0.05, ground);
  EXPECT_EQ(takeoff.commands.at(0).command, mavlink::cmd::kNavTakeoff);
  pilot.on_board_frame(board.ack(mavlink::cmd::kNavTakeoff));
  PilotPose up = ground;
  up.p_ENU_m[2] = 2.0;
  float main_mode = -1;
  bool centred_sticks_first = false;
  for (int i = 0; i < 40 && main_mode < 0; ++i) {
    auto out = pilot.step(t_s += 0.05, up);
    if (out.rc && main_mode < 0) centred_sticks_first = out.rc->chan1_raw == 1500 && out.rc->chan3_raw == 1500;
    for (const auto& c : out.commands)
      if (c.command == mavlink::cmd::kDoSetMode) main_mode = c.param2;
  }
  EXPECT_TRUE(centred_sticks_first) << "a manual mode needs manual control present before the switch";
  // PX4 SITL acknowledged a DO_SET_MODE as accepted and then refused the switch: the ACK is not the mode.
  pilot.on_board_frame(board.ack(mavlink::cmd::kDoSetMode));
  pilot.step(t_s += 0.05, up);
  EXPECT_EQ(pilot.state(), PilotState::Takeoff);
  pilot.on_board_frame(board.heartbeat(true, static_cast<uint32_t>(main_mode) << 16));  // the board shows it
  pilot.step(t_s += 0.05, up);
  EXPECT_EQ(pilot.state(), PilotState::Trajectory);
  return main_mode;
}

/// Ready, armed, its takeoff requested and acknowledged: the pilot in TAKEOFF, on the ground at `pose`.
void to_acknowledged_takeoff(TrajectoryPilot& pilot, Board& board, double& t_s, const PilotPose& pose) {
  pilot.on_board_frame(board.ready());
  pilot.step(t_s += 0.05, pose);
  pilot.step(t_s += 0.05, pose);
  pilot.on_board_frame(board.heartbeat(true));
  pilot.step(t_s += 0.05, pose);
  pilot.step(t_s += 0.05, pose);
  pilot.on_board_frame(board.ack(mavlink::cmd::kNavTakeoff));
}

/// To TAKEOFF, the takeoff acknowledged, the vehicle stopped at `short_pose` below the 2 m height;
/// then `hb_modes` as the board's HEARTBEATs (armed). Whether the pilot went on to ask for its mode.
bool asks_for_its_mode_after(std::initializer_list<Px4Mode> hb_modes) {
  Board board;
  TrajectoryPilot pilot(square(), PilotConfig{});
  double t_s = 0;
  PilotPose ground;
  to_acknowledged_takeoff(pilot, board, t_s, ground);
  PilotPose short_pose = ground;
  short_pose.p_ENU_m[2] = 1.2;  // 0.8 m short: PX4 v1.16 ended takeoffs 0.6-1.1 m short
  for (const Px4Mode m : hb_modes) {
    pilot.on_board_frame(board.heartbeat(true, m.custom_mode()));
    pilot.step(t_s += 0.05, short_pose);
  }
  for (int i = 0; i < 60; ++i) {
    for (const auto& c : pilot.step(t_s += 0.05, short_pose).commands)
      if (c.command == mavlink::cmd::kDoSetMode) return true;
  }
  return false;
}

TEST(TrajectoryPilot, GoesOnWhenTheBoardEndsItsTakeoffShortOfTheHeight) {
  EXPECT_FALSE(asks_for_its_mode_after({kPx4Takeoff})) << "still taking off, and short: it waits";
  EXPECT_TRUE(asks_for_its_mode_after({kPx4Takeoff, kPx4Hold})) << "the board ended its takeoff and holds";
  EXPECT_FALSE(asks_for_its_mode_after({kPx4Takeoff, Px4Mode{4, 6}})) << "a Land failsafe is no end of the takeoff";
  EXPECT_FALSE(asks_for_its_mode_after({kPx4Hold})) << "Hold before any takeoff is no end of it";
}

TEST(TrajectoryPilot, ClimbsTheRestInItsModeBeforeTheTrajectorysClockStarts) {
  Board board;
  TrajectoryPilot pilot(square(), PilotConfig{});
  double t_s = 0;
  PilotPose pose;
  pose.yaw_ENU_rad = M_PI / 2;
  to_acknowledged_takeoff(pilot, board, t_s, pose);
  pose.p_ENU_m[2] = 1.2;  // the board's takeoff ends 0.8 m short of the square's 2 m
  pilot.on_board_frame(board.heartbeat(true, kPx4Takeoff.custom_mode()));
  pilot.on_board_frame(board.heartbeat(true, kPx4Hold.custom_mode()));
  for (int i = 0; i < 40; ++i) pilot.step(t_s += 0.05, pose);
  pilot.on_board_frame(board.heartbeat(true, kPx4Position.custom_mode()));  // the sticks' mode taken
  // Still TAKEOFF, the sticks climbing (throttle above centre), no tracking yet.
  bool climbed = false;
  for (int i = 0; i < 10; ++i) {
    const auto out = pilot.step(t_s += 0.05, pose);
    EXPECT_FALSE(out.tracking_error_m);
    if (out.rc && out.rc->chan3_raw > 1550) climbed = true;
  }
  EXPECT_TRUE(climbed);
  EXPECT_EQ(pilot.state(), PilotState::Takeoff);
  pose.p_ENU_m[2] = 1.9;  // within 0.3 m: the trajectory starts
  const auto out = pilot.step(t_s += 0.05, pose);
  EXPECT_EQ(pilot.state(), PilotState::Trajectory);
  ASSERT_TRUE(out.event);
  EXPECT_EQ(*out.event, "trajectory: TRAJECTORY (at 2.00 m, Position mode; the board ended its takeoff 0.80 m short, the sticks climbed the rest)");
}

TEST(TrajectoryPilot, VelocityModeFliesPositionModeWithVelocitySticks) {
  Board board;
  TrajectoryPilot pilot(square(), PilotConfig{});
  double t_s = 0;
  EXPECT_EQ(fly_to_trajectory(pilot, board, t_s), 3.0f);  // POSCTL
  // Facing north, 3 m south of the reference: pitch forward, no roll, climb neutral.
  PilotPose behind;
  behind.yaw_ENU_rad = M_PI / 2;
  behind.p_ENU_m = {0, -3, 2};
  auto out = pilot.step(t_s += 0.1, behind);
  ASSERT_TRUE(out.rc);
  EXPECT_GT(out.rc->chan2_raw, 1550);
  EXPECT_EQ(out.rc->chan1_raw, 1500);
  EXPECT_EQ(out.rc->chan3_raw, 1500);
}

TEST(TrajectoryPilot, AttitudeModeFliesStabilizedWithTiltAndThrust) {
  Board board;
  PilotConfig config;
  config.mode = StickMode::Attitude;
  TrajectoryPilot pilot(square(), config);
  double t_s = 0;
  EXPECT_EQ(fly_to_trajectory(pilot, board, t_s), 7.0f);  // STABILIZED

  PilotPose on_track;
  on_track.yaw_ENU_rad = M_PI / 2;
  on_track.p_ENU_m = {0, 0, 2};
  on_track.v_ENU_m_s = {0, 0, 0};
  auto out = pilot.step(t_s += 0.1, on_track);
  ASSERT_TRUE(out.rc);
  // The reference moves north at 1 m/s: tilt forward; height right: throttle near hover (mid).
  EXPECT_GT(out.rc->chan2_raw, 1500);
  EXPECT_NEAR(out.rc->chan1_raw, 1500, 2);
  EXPECT_NEAR(out.rc->chan3_raw, 1500, 40);

  // 1 m low and sinking: more thrust than hover.
  PilotPose low = on_track;
  low.p_ENU_m[2] = 1.0;
  low.v_ENU_m_s = {0, 1, -0.5};
  out = pilot.step(t_s += 0.1, low);
  ASSERT_TRUE(out.rc);
  EXPECT_GT(out.rc->chan3_raw, 1600);
  // Far east of the track, facing north: roll left (to the west).
  PilotPose east = on_track;
  east.p_ENU_m = {5, 1, 2};
  east.v_ENU_m_s = {0, 1, 0};
  out = pilot.step(t_s += 0.1, east);
  ASSERT_TRUE(out.rc);
  EXPECT_LT(out.rc->chan1_raw, 1450);
}

TEST(TrajectoryPilot, TruthIsScoredOnlyWhileFlyingTheTrajectory) {
  Board board;
  TrajectoryPilot pilot(square(), PilotConfig{});
  PilotPose truth;
  truth.p_ENU_m = {3, 0, 0};
  pilot.observe_truth(0, truth);  // INIT: not scored
  EXPECT_EQ(pilot.truth_tracking().samples, 0u);
  double t_s = 0;
  fly_to_trajectory(pilot, board, t_s);
  truth.p_ENU_m = {3, 4, 2};  // 3 m east and 4 m ahead of where the reference is at t = 0
  const double start = t_s;
  pilot.observe_truth(start, truth);
  const auto s = pilot.truth_tracking();
  EXPECT_EQ(s.samples, 1u);
  EXPECT_NEAR(s.rms_m, 5.0, 0.2);  // the reference has moved at most 0.05 m since
}

TEST(TrajectoryPilot, ThrottleIsTheInverseOfTheBoardsThrottleCurve) {
  PilotConfig config;
  flight::FlightParams board;
  config.thr_hover = board.MPC_THR_HOVER;
  config.thr_min = board.MPC_MANTHR_MIN;
  config.thr_max = board.MPC_THR_MAX;
  for (double thrust : {0.1, 0.3, 0.59, 0.7, 0.95}) {
    EXPECT_NEAR(flight::manual_thrust(throttle_for_thrust(thrust, config), board), thrust, 1e-9) << thrust;
  }
  EXPECT_EQ(throttle_for_thrust(2.0, config), 1.0);  // beyond full stick: clamped
  EXPECT_EQ(throttle_for_thrust(0.0, config), 0.0);
}

}  // namespace
}  // namespace hitl::vehicle
