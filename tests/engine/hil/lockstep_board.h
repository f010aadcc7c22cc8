// A stand-in board that flies a session in lockstep for the faults' model tests: it answers each
// HIL_SENSOR with the same command on every motor (armed, a function of simulated time) and keeps
// every HIL_SENSOR and HIL_GPS it got, by time_usec. The session runs as fast as it can, to its
// duration, on the test's thread: what the board saw depends on the steps only.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/hil/session.h"
#include "tests/engine/hil/stand_in_session_config.h"
#include "engine/model/x500_defaults.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl::hil::test_lockstep {

struct Seen {
  std::map<uint64_t, mavlink::msg::HilSensor> sensors;  ///< by time_usec
  std::map<uint64_t, mavlink::msg::HilGps> gps;
  std::vector<uint64_t> arrivals;  ///< each HIL_SENSOR's time_usec as it arrived (repeats and order as on the wire)
};

/// The motor command (0..1, every motor) the board answers the HIL_SENSOR of `time_us` with.
using Command = std::function<double(uint64_t time_us)>;

/// A lockstep session to `duration_s` with `faults` (noise off unless `noise`) against the board;
/// `tweak` changes the rest of its config.
inline Seen fly(const std::vector<std::string>& faults, double duration_s, const Command& command, bool noise = false,
                uint64_t seed = 1, const std::function<void(SessionConfig&)>& tweak = {}) {
  namespace msg = mavlink::msg;
  test::MavlinkPeer board(0, 0);
  SessionConfig c = test_session::stand_in_session_config(board.endpoint().local_address().port(), faults);
  c.noise = noise;
  c.seed = seed;
  c.lockstep = true;
  c.speed = 0;
  c.duration_s = duration_s;
  if (tweak) tweak(c);
  auto session = Session::create(c);
  EXPECT_TRUE(session) << session.error().message;
  if (!session) return {};

  Seen seen;
  std::atomic<bool> done{false};
  std::thread answering([&] {
    const auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    while (!done) {
      if (!board.endpoint().wait_readable(20)) continue;
      while (auto d = board.endpoint().receive())
        parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
          if (f.is<msg::HilGps>()) seen.gps[f.as<msg::HilGps>().time_usec] = f.as<msg::HilGps>();
          if (!f.is<msg::HilSensor>()) return;
          const auto s = f.as<msg::HilSensor>();
          seen.sensors[s.time_usec] = s;
          seen.arrivals.push_back(s.time_usec);
          msg::HilActuatorControls a;
          a.time_usec = s.time_usec;  // lockstep: the answer to this HIL_SENSOR
          a.controls = {};
          for (std::size_t i = 0; i < 4; ++i) a.controls[i] = static_cast<float>(command(s.time_usec));
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
  return seen;
}

/// The mean of `value` over the entries of `by_time` with time_usec in [from_s, to_s).
template <typename M, typename F>
double mean_over(const std::map<uint64_t, M>& by_time, double from_s, double to_s, F value) {
  double sum = 0;
  int n = 0;
  for (auto it = by_time.lower_bound(static_cast<uint64_t>(from_s * 1e6 + 0.5)); it != by_time.end() && it->first < to_s * 1e6 - 0.5; ++it)
    sum += value(it->second), ++n;
  EXPECT_GT(n, 0) << from_s << ".." << to_s << " s";
  return n ? sum / n : 0;
}

}  // namespace hitl::hil::test_lockstep
