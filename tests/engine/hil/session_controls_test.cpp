// The session's operator controls (the dashboard's p and r keys) and its live data paths.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "base/mavlink/messages.h"
#include "engine/hil/data_paths.h"
#include "engine/hil/session.h"
#include "engine/model/x500_defaults.h"
#include "tests/engine/hil/stand_in_session_config.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl::hil {
namespace {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;

class Events : public Session::Observer {
 public:
  void on_event(const SessionEvent& e) override {
    std::lock_guard<std::mutex> lock(mutex_);
    texts_ += e.text + "\n";
  }
  std::string texts() {
    std::lock_guard<std::mutex> lock(mutex_);
    return texts_;
  }

 private:
  std::mutex mutex_;
  std::string texts_;
};

/// HIL_SENSOR timestamps that arrived at the stand-in board within `wait`.
std::vector<uint64_t> sensor_times(test::MavlinkPeer& board, std::chrono::milliseconds wait) {
  std::vector<uint64_t> t;
  for (const auto& f : board.receive_for(wait))
    if (f.is<msg::HilSensor>()) t.push_back(f.as<msg::HilSensor>().time_usec);
  return t;
}

TEST(SessionControls, PauseHoldsAndSendsNothingResetKeepsTheWireClock) {
  test::MavlinkPeer board(0, 0);
  SessionConfig c = test_session::stand_in_session_config(board.endpoint().local_address().port());
  auto session = Session::create(c);
  ASSERT_TRUE(session) << session.error().message;
  Session& s = **session;
  Events events;
  std::atomic<bool> stop{false};
  std::thread loop([&] { (void)s.run(stop, events); });

  auto running = sensor_times(board, 500ms);
  ASSERT_GT(running.size(), 20u);

  s.set_paused(true);
  std::this_thread::sleep_for(200ms);
  (void)board.receive_for(50ms);  // whatever was in flight
  EXPECT_TRUE(sensor_times(board, 400ms).empty()) << "HIL_SENSOR while paused";
  const auto held = s.snapshot();
  std::this_thread::sleep_for(300ms);
  EXPECT_TRUE(s.snapshot().paused);
  EXPECT_DOUBLE_EQ(s.snapshot().sim_time_s, held.sim_time_s) << "the model moved while paused";

  s.set_paused(false);
  auto resumed = sensor_times(board, 400ms);
  ASSERT_GT(resumed.size(), 10u);
  EXPECT_GT(resumed.front(), running.back());
  // Wall time spent paused is not simulated time: the clock picks up where it stopped.
  EXPECT_LT(resumed.front() - running.back(), 300000u);

  const double before_reset_s = s.snapshot().sim_time_s;
  s.request_reset();
  auto after = sensor_times(board, 400ms);
  ASSERT_GT(after.size(), 10u);
  for (std::size_t i = 1; i < after.size(); ++i) EXPECT_GT(after[i], after[i - 1]) << "the wire's clock went back at " << i;
  EXPECT_GT(after.front(), resumed.back());
  const auto snap = s.snapshot();
  EXPECT_EQ(snap.resets, 1u);
  EXPECT_GT(snap.sim_time_s, before_reset_s);
  EXPECT_TRUE(snap.on_ground);

  stop.store(true);
  loop.join();
  const auto texts = events.texts();
  EXPECT_NE(texts.find("paused at"), std::string::npos) << texts;
  EXPECT_NE(texts.find("resumed at"), std::string::npos) << texts;
  EXPECT_NE(texts.find("reset to home"), std::string::npos) << texts;
}

TEST(DataPaths, RatesByFieldsUpdatedAndLossFromSequenceGaps) {
  SessionConfig c;
  c.vehicle = model::x500_vehicle_config();
  DataPaths paths(c, /*lockstep=*/false);
  const double t0 = 100.0;
  for (int k = 0; k < 250; ++k) paths.on_hil_sensor(true, k % 5 == 0, k % 25 == 0, t0 + k * 0.004);
  for (int k = 0; k < 30; ++k) paths.on_hil_gps(t0 + k / 30.0);
  for (int k = 0; k < 250; ++k) paths.on_odometry(t0 + k * 0.004);
  mavlink::Frame f;
  f.msgid = msg::HilActuatorControls::kId;
  f.sysid = 1;
  f.compid = 1;
  for (uint8_t seq : {0, 1, 2, 5}) {  // 3 and 4 lost
    f.seq = seq;
    paths.on_stack_frame(f, t0 + seq * 0.005);
  }
  paths.roll(t0 + 1.0, 2.0);  // at --speed 2
  const auto s = paths.stats(t0 + 1.0);
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s[0].name, "IMU");
  EXPECT_NEAR(s[0].stats.rate_hz, 250.0, 1e-6);
  EXPECT_NEAR(s[0].expected_hz, 2 * c.vehicle.sensors.imu.rate_hz, 1e-9);
  EXPECT_NEAR(s[1].stats.rate_hz, 50.0, 1e-6);
  EXPECT_NEAR(s[2].stats.rate_hz, 10.0, 1e-6);
  EXPECT_EQ(s[3].message, "HIL_GPS");
  EXPECT_EQ(s[4].name, "ODOMETRY");
  EXPECT_EQ(s[5].name, "actuators");
  EXPECT_FALSE(s[5].outgoing);
  EXPECT_DOUBLE_EQ(s[5].expected_hz, kActuatorStreamRate_hz);  // the board's clock: not scaled
  ASSERT_TRUE(s[5].loss_pct.has_value());
  EXPECT_NEAR(*s[5].loss_pct, 100.0 * 2 / 6, 1e-9);
  EXPECT_FALSE(s[0].loss_pct.has_value());  // the host cannot see what the board lost

  // Lockstep: one answer per sensor message; no ODOMETRY with --no-vio.
  c.lockstep = true;
  c.vio = false;
  DataPaths lockstep(c, /*lockstep=*/true);
  lockstep.roll(1.0, 1.0);
  const auto l = lockstep.stats(1.0);
  ASSERT_EQ(l.size(), 5u);
  EXPECT_DOUBLE_EQ(l.back().expected_hz, c.vehicle.sensors.imu.rate_hz);
}

}  // namespace
}  // namespace hitl::hil
