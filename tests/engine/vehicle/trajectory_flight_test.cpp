// One trajectory flight: its origins (the pose's and the truth's, each where it was at rest), and
// fly_trajectory() over a link against a scripted board that runs its clock five times faster than
// the wall (the flight goes by the board's time_boot_ms): NED converted to ENU, the whole sequence
// to DONE, what it says as it goes, the trace; stopping; no estimate.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>
#include <vector>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "engine/vehicle/action.h"
#include "engine/vehicle/trajectory_flight.h"
#include "tests/support/board_link.h"
#include "tests/support/scripted_board.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
using namespace std::chrono_literals;
using test::ScriptedBoard;
using test::connect_to;

/// Hover 2 m above the start, facing east (ENU yaw 0), for 1 s.
Trajectory hover() {
  auto t = Trajectory::parse(R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0},
                                              {"t": 1, "x": 0, "y": 0, "z": 2, "yaw": 0}]})",
                             "hover.json");
  EXPECT_TRUE(t.ok());
  return *t;
}

/// A frame as the board (sysid 1) sends it.
template <class M>
mavlink::Frame board_frame(const M& m) {
  static const mavlink::MessageSet set = mavlink::MessageSet::compiled();
  mavlink::FrameEncoder encoder(1, 1);
  mavlink::FrameParser parser(set);
  mavlink::FrameBuffer buf;
  const std::size_t n = encoder.encode(m, buf);
  std::optional<mavlink::Frame> out;
  parser.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) { out = f; });
  return *out;
}

mavlink::Frame ack(uint16_t command) {
  msg::CommandAck a;
  a.command = command;
  a.result = static_cast<uint8_t>(mavlink::MavResult::Accepted);
  return board_frame(a);
}

PilotPose at(std::array<double, 3> p_ENU_m) {
  PilotPose pose;
  pose.p_ENU_m = p_ENU_m;
  return pose;
}

TEST(TrajectoryFlight, PoseAndTruthAreMeasuredFromWhereEachRestedAtTheStart) {
  TrajectoryFlight flight(hover(), PilotConfig{}, /*keep_trace=*/true);
  const std::array<double, 3> home{100, 50, 0.2}, truth_home{-3, 4, 0};
  double t_s = 7.0;  // any clock: the first tick is the flight's zero
  auto tick = [&](double up_m, double truth_off_m) {
    flight.step(t_s += 0.05, at({home[0], home[1], home[2] + up_m}), at({truth_home[0] + truth_off_m, truth_home[1], truth_home[2] + up_m}));
  };
  tick(0, 0);
  EXPECT_EQ(flight.state(), PilotState::Init);
  msg::SysStatus ready;
  ready.onboard_control_sensors_health = mavlink::sys_status::kPrearmCheck;
  flight.on_board_frame(board_frame(ready));
  tick(0, 0);
  msg::Heartbeat armed;
  armed.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Px4);
  armed.base_mode = mavlink::mode_flag::kSafetyArmed;
  flight.on_board_frame(board_frame(armed));
  tick(0, 0);
  EXPECT_EQ(flight.state(), PilotState::Takeoff);
  flight.on_board_frame(ack(mavlink::cmd::kNavTakeoff));
  for (int i = 0; i < 10; ++i) tick(2.0, 0.5);
  armed.custom_mode = kPx4Position.custom_mode();  // the board shows the mode asked for
  flight.on_board_frame(board_frame(armed));
  for (int i = 0; i < 10; ++i) tick(2.0, 0.5);
  ASSERT_EQ(flight.state(), PilotState::Trajectory);
  const auto r = flight.result();
  EXPECT_GT(r.tracking.samples, 0u);
  EXPECT_NEAR(r.tracking.rms_m, 0.0, 1e-9);  // exactly on the reference, 2 m above where it rested
  EXPECT_NEAR(r.truth_tracking.rms_m, 0.5, 1e-9);
  ASSERT_FALSE(r.trace.empty());
  EXPECT_NEAR(r.trace.back().p_ENU_m[2], 2.0, 1e-9);
  ASSERT_TRUE(r.trace.back().truth_p_ENU_m);
  EXPECT_NEAR((*r.trace.back().truth_p_ENU_m)[0], 0.5, 1e-9);
}

/// A board flying the pilot's requests by teleport: on the ground at NED (10, 20, 0) facing east,
/// 2 m up after NAV_TAKEOFF, landed and disarmed after NAV_LAND; the simulator's truth (sysid 250)
/// half a metre further north than the estimate once up. Its clock runs at 5x.
class FlyingBoard {
 public:
  explicit FlyingBoard(bool ready = true)
      : board_([this](const mavlink::Frame& f, test::MavlinkPeer& peer) { on_frame(f, peer); },
               [this, ready](test::MavlinkPeer& peer) { tick(peer, ready); }) {}
  uint16_t port() { return board_.port(); }
  float takeoff_amsl_m() const { return takeoff_amsl_m_.load(); }
  int rc_overrides() const { return rc_.load(); }

 private:
  void on_frame(const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (f.is<msg::RcChannelsOverride>()) ++rc_;
    if (!f.is<msg::CommandLong>()) return;
    const auto c = f.as<msg::CommandLong>();
    if (c.command == mavlink::cmd::kComponentArmDisarm) board_.base_mode = c.param1 == 1.0f ? mavlink::mode_flag::kSafetyArmed : 0;
    if (c.command == mavlink::cmd::kNavTakeoff) {
      takeoff_amsl_m_ = c.param7;
      up_ = true;
    }
    if (c.command == mavlink::cmd::kDoSetMode)  // shown from the next HEARTBEAT on, as PX4 does
      board_.custom_mode = static_cast<uint32_t>(c.param2) << 16 | static_cast<uint32_t>(c.param3) << 24;
    if (c.command == mavlink::cmd::kNavLand) {
      up_ = false;
      board_.base_mode = 0;
    }
    msg::CommandAck a;
    a.command = c.command;
    a.result = static_cast<uint8_t>(mavlink::MavResult::Accepted);
    peer.send(a);
  }
  void tick(test::MavlinkPeer& peer, bool ready) {
    time_boot_ms_ += 100;
    const float z_NED_m = up_ ? -2.0f : 0.0f;
    msg::SysStatus s;
    if (ready) s.onboard_control_sensors_health = mavlink::sys_status::kPrearmCheck;
    peer.send(s);
    msg::LocalPositionNed l;
    l.time_boot_ms = time_boot_ms_;
    l.x = 10;
    l.y = 20;
    l.z = z_NED_m;
    peer.send(l);
    msg::Attitude a;
    a.time_boot_ms = time_boot_ms_;
    a.yaw = static_cast<float>(M_PI / 2);  // heading east: ENU yaw 0
    peer.send(a);
    msg::GlobalPositionInt g;
    g.time_boot_ms = time_boot_ms_;
    g.relative_alt = static_cast<int32_t>(-z_NED_m * 1000);
    g.alt = 488000 + g.relative_alt;
    peer.send(g);
    msg::Odometry truth;
    truth.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
    truth.x = up_ ? -4.5f : -5.0f;
    truth.y = 7;
    truth.z = z_NED_m - 0.5f;
    mavlink::FrameBuffer buf;
    peer.send_bytes({buf.data(), truth_encoder_.encode(truth, buf)});
  }

  std::atomic<bool> up_{false};
  std::atomic<float> takeoff_amsl_m_{0};
  std::atomic<int> rc_{0};
  uint32_t time_boot_ms_ = 1000;
  mavlink::FrameEncoder truth_encoder_{250, 1};
  ScriptedBoard board_;  ///< last: its thread starts once the rest is built
};

TEST(FlyTrajectory, FliesTheWholeSequenceOnTheBoardsEstimateInEnu) {
  FlyingBoard board;
  auto link = connect_to(board.port());
  FlyTrajectoryOptions o;
  o.truth_sysid = 250;
  o.keep_trace = true;
  std::mutex mutex;
  std::vector<std::string> notes;
  auto flown = fly_trajectory(*link, hover(), o, [&](const std::string& text) {
    std::lock_guard<std::mutex> lock(mutex);
    notes.push_back(text);
  });
  ASSERT_TRUE(flown.ok()) << flown.error().message;
  const FlightResult& r = *flown;
  EXPECT_TRUE(r.ok()) << r.text();
  EXPECT_FALSE(r.stopped);
  EXPECT_FLOAT_EQ(board.takeoff_amsl_m(), 490.0f);  // home 488 m from GLOBAL_POSITION_INT, + 2 m
  EXPECT_GT(board.rc_overrides(), 0);
  EXPECT_GT(r.tracking.samples, 0u);
  EXPECT_NEAR(r.tracking.rms_m, 0.0, 1e-6);  // NED (10, 20, -2) from rest at (10, 20, 0): ENU (0, 0, 2)
  EXPECT_GT(r.truth_tracking.samples, 0u);
  EXPECT_NEAR(r.truth_tracking.rms_m, 0.5, 1e-6);  // half a metre north: ENU y
  ASSERT_FALSE(r.trace.empty());
  ASSERT_TRUE(r.trace.front().truth_p_ENU_m);
  EXPECT_NEAR((*r.trace.front().truth_p_ENU_m)[1], 0.5, 1e-6);
  EXPECT_EQ(r.text().rfind("DONE; velocity mode; tracking error (board's estimate) RMS 0.00 m, max 0.00 m; against the "
                           "simulator's truth RMS 0.50 m",
                           0),
            0u)
      << r.text();
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_FALSE(notes.empty());
  EXPECT_EQ(notes.front(), "trajectory: ARM (the board is ready to arm)");
  EXPECT_EQ(notes.back(), "trajectory: DONE (landed and disarmed)");
}

TEST(FlyTrajectory, StopsWhenAskedAndSaysWhereItWas) {
  FlyingBoard board(/*ready=*/false);  // never ready to arm: the flight waits in INIT
  std::atomic<bool> stop{false};
  auto link = connect_to(board.port(), &stop);
  FlyTrajectoryOptions o;
  o.stop = &stop;
  std::thread stopper([&] {
    std::this_thread::sleep_for(500ms);
    stop = true;
  });
  auto flown = fly_trajectory(*link, hover(), o);
  stopper.join();
  ASSERT_TRUE(flown.ok()) << flown.error().message;
  EXPECT_TRUE(flown->stopped);
  EXPECT_EQ(flown->state, PilotState::Init);
  EXPECT_FALSE(flown->ok());
}

TEST(FlyTrajectory, NoEstimateFromTheBoardIsAnError) {
  ScriptedBoard board([](const mavlink::Frame& f, test::MavlinkPeer& peer) {
    if (!f.is<msg::CommandLong>()) return;
    msg::CommandAck a;
    a.command = f.as<msg::CommandLong>().command;
    peer.send(a);
  });
  auto link = connect_to(board.port());
  FlyTrajectoryOptions o;
  o.estimate_wait_s = 0.5;
  auto flown = fly_trajectory(*link, hover(), o);
  ASSERT_FALSE(flown.ok());
  EXPECT_EQ(flown.error().message, "no position estimate from the board (LOCAL_POSITION_NED, GLOBAL_POSITION_INT)");
}

}  // namespace
}  // namespace hitl::vehicle
