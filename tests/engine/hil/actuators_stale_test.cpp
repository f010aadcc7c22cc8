// actuators-stale in the session (docs/faults.md): the board's actuator stream goes stale, the
// model holds the last commands it had. A stand-in board answers each HIL_SENSOR in lockstep with
// 0.9 on every motor until 1 s, then 0.3, and reads the thrust back off the HIL_SENSORs it gets
// (noise off: zacc is the rotors' thrust over the mass, less drag): under the fault the thrust
// stays 0.9's while the board asks for 0.3, and follows it from the step after the fault ends.
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <mutex>
#include <thread>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/hil/session.h"
#include "engine/model/x500_defaults.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl::hil {
namespace {

namespace msg = mavlink::msg;

constexpr double kBefore = 0.9, kAfter = 0.3;  ///< the board's command before and after 1 s

/// zacc (FRD, m/s^2) of every HIL_SENSOR the board got, by time_usec, over a lockstep session to
/// 1.8 s with `faults`.
std::map<uint64_t, double> fly(const std::vector<std::string>& faults) {
  test::MavlinkPeer board(0, 0);
  SessionConfig c;
  c.target_ip = "127.0.0.1";
  c.hil_port = board.endpoint().local_address().port();
  c.local_port = test::free_udp_port();
  c.vio = false;
  c.clients_port = 0;
  c.noise = false;
  c.lockstep = true;
  c.speed = 0;
  c.duration_s = 1.8;
  c.vehicle = model::x500_vehicle_config();
  c.world = model::default_world_config();
  for (const auto& f : faults) c.faults.push_back(*faults::parse_fault(f));
  auto session = Session::create(c);
  EXPECT_TRUE(session) << session.error().message;
  if (!session) return {};

  std::map<uint64_t, double> zacc;
  std::atomic<bool> done{false};
  std::thread answering([&] {
    const auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    while (!done) {
      if (!board.endpoint().wait_readable(20)) continue;
      while (auto d = board.endpoint().receive())
        parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
          if (!f.is<msg::HilSensor>()) return;
          const auto s = f.as<msg::HilSensor>();
          zacc[s.time_usec] = s.zacc;
          msg::HilActuatorControls a;
          a.time_usec = s.time_usec;  // lockstep: the answer to this HIL_SENSOR
          a.controls = {};
          for (std::size_t i = 0; i < 4; ++i) a.controls[i] = static_cast<float>(s.time_usec < 1'000'000 ? kBefore : kAfter);
          a.mode = mavlink::mode_flag::kCustomModeEnabled | mavlink::mode_flag::kHilEnabled | mavlink::mode_flag::kSafetyArmed;
          a.flags = 0x0F;
          board.send(a);
        });
    }
  });
  std::atomic<bool> stop{false};
  Session::Observer observer;
  const auto end = (*session)->run(stop, observer);
  done = true;
  answering.join();
  EXPECT_TRUE(end) << end.error().message;
  return zacc;
}

/// The mean zacc over time_usec in [from_s, to_s).
double mean_zacc(const std::map<uint64_t, double>& zacc, double from_s, double to_s) {
  double sum = 0;
  int n = 0;
  for (auto it = zacc.lower_bound(static_cast<uint64_t>(from_s * 1e6)); it != zacc.end() && it->first < to_s * 1e6; ++it)
    sum += it->second, ++n;
  EXPECT_GT(n, 20) << from_s << ".." << to_s << " s";
  return n ? sum / n : 0;
}

TEST(ActuatorsStale, TheThrustStaysTheLastCommandsWhileTheBoardAsksForLessAndFollowsAfter) {
  const auto zacc = fly({"actuators-stale@0.5+0.8"});  // 0.5 .. 1.3 s
  const double held = mean_zacc(zacc, 0.6, 1.0);       // the board asks for 0.9, the model has it
  const double stale = mean_zacc(zacc, 1.05, 1.3);     // the board asks for 0.3, the model holds 0.9
  const double after = mean_zacc(zacc, 1.4, 1.8);      // the fault over: 0.3
  std::printf("zacc (m/s^2): 0.9 commanded %.2f, 0.3 commanded but stale %.2f, 0.3 after the fault %.2f\n", held, stale, after);
  EXPECT_LT(held, -10.0);  // 0.9: thrust 4 kF (900 rad/s)^2 = 27.7 N on about 2 kg
  EXPECT_LT(stale, -10.0) << "the thrust must not follow the board's new command while stale";
  EXPECT_GT(after, -4.0);  // 0.3: 3.1 N
}

TEST(ActuatorsStale, WithoutItTheThrustFollowsTheBoard) {
  const auto zacc = fly({});
  EXPECT_LT(mean_zacc(zacc, 0.6, 1.0), -10.0);
  EXPECT_GT(mean_zacc(zacc, 1.05, 1.3), -4.0);
}

}  // namespace
}  // namespace hitl::hil
