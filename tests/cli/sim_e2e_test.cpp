// hitl sim end to end: the real binary; a loopback peer plays the board (answers HIL_SENSOR with
// HIL_ACTUATOR_CONTROLS) and checks what the simulator sends: rates, fields_updated cadence,
// frames and units, hover, motor timeout, clamping, lockstep, ignored senders, routing, PX4 SITL.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <nlohmann/json.hpp>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <deque>
#include <csignal>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <thread>

#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/hil_sensor_fields.h"
#include "base/mavlink/messages.h"
#include "engine/model/x500_defaults.h"
#include "tests/support/json_lines.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;
namespace msg = mavlink::msg;
using test::Process;

const double kHover = model::hover_command(model::x500_vehicle_config(), model::default_world_config());

nlohmann::json last_json(const std::string& out) { return test::last_json_line(out); }

msg::HilActuatorControls actuators(double u, bool armed) {
  msg::HilActuatorControls a;
  a.controls = {};
  for (int i = 0; i < 4; ++i) a.controls[static_cast<std::size_t>(i)] = static_cast<float>(u);
  a.mode = mavlink::mode_flag::kCustomModeEnabled | mavlink::mode_flag::kHilEnabled | (armed ? mavlink::mode_flag::kSafetyArmed : 0);
  a.flags = 0x0F;
  return a;
}

/// Plays the board's HIL instance: records every frame, answers each HIL_SENSOR via `answer`.
class Board {
 public:
  Board() : port_(test::free_udp_port()), sim_port_(test::free_udp_port()), vio_port_(test::free_udp_port()), peer_(port_, sim_port_) {}
  ~Board() { stop(); }

  std::vector<std::string> sim_args(std::initializer_list<std::string> extra) const {
    std::vector<std::string> a{test::hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(port_),
                               "--local-port", std::to_string(sim_port_), "--vio-port", std::to_string(vio_port_),
                               "--clients", "0"};
    a.insert(a.end(), extra);
    return a;
  }

  /// Starts answering: `answer(sensor, index)` returns the controls to send back, or nothing.
  void serve(std::function<std::optional<msg::HilActuatorControls>(const msg::HilSensor&, uint64_t)> answer) {
    running_ = true;
    thread_ = std::thread([this, answer]() {
      auto set = mavlink::MessageSet::compiled();
      mavlink::FrameParser parser(set);
      uint64_t n = 0;
      while (running_) {
        if (!peer_.endpoint().wait_readable(20)) continue;
        while (auto d = peer_.endpoint().receive()) {
          parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
            {
              std::lock_guard<std::mutex> lock(mutex_);
              frames_.push_back(f);
            }
            if (!f.is<msg::HilSensor>()) return;
            if (auto a = answer(f.as<msg::HilSensor>(), n++)) peer_.send(*a);
          });
        }
      }
    });
  }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }
  std::vector<mavlink::Frame> frames() {
    std::lock_guard<std::mutex> lock(mutex_);
    return frames_;
  }
  test::MavlinkPeer& peer() { return peer_; }
  uint16_t port() const { return port_; }
  uint16_t sim_port() const { return sim_port_; }
  uint16_t vio_port() const { return vio_port_; }

 private:
  uint16_t port_, sim_port_, vio_port_;
  test::MavlinkPeer peer_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::mutex mutex_;
  std::vector<mavlink::Frame> frames_;
};

TEST(SimE2E, SendsHilSensorWithExactFieldsUpdatedCadenceAndUnits) {
  Board board;
  test::MavlinkPeer vio(board.vio_port(), 0);
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "2", "--speed", "0"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  std::this_thread::sleep_for(200ms);
  board.stop();
  const auto frames = board.frames();
  namespace bits = mavlink::hil_sensor;
  int sensors = 0, mags = 0, baros = 0, gps = 0, heartbeats = 0, last_mag = 0, last_baro = 0;
  uint64_t last_t = 0;
  for (const auto& f : frames) {
    EXPECT_EQ(f.sysid, 250);
    if (f.is<msg::HilSensor>()) {
      const auto s = f.as<msg::HilSensor>();
      ++sensors;
      EXPECT_EQ(s.time_usec, last_t + 4000) << "HIL_SENSOR " << sensors;  // PX4 SITL's clock: > 0, one step apart
      last_t = s.time_usec;
      EXPECT_EQ(s.fields_updated & (bits::kAccel | bits::kGyro), bits::kAccel | bits::kGyro);
      const bool mag = (s.fields_updated & bits::kMag) != 0;
      const bool baro = (s.fields_updated & bits::kBaro) != 0;
      EXPECT_TRUE((s.fields_updated & bits::kMag) == 0 || (s.fields_updated & bits::kMag) == bits::kMag);
      EXPECT_TRUE((s.fields_updated & bits::kBaro) == 0 || (s.fields_updated & bits::kBaro) == bits::kBaro);
      EXPECT_EQ(s.fields_updated & bits::kDiffPressure, 0u);
      if (mag) {
        // The samples due at t = 0 go out with the first step (t = 4 ms: PX4 SITL needs time_usec > 0),
        // so the cadence is exact from the second sample on.
        if (mags > 1) {
          EXPECT_EQ(sensors - last_mag, 5) << "mag every 5th HIL_SENSOR (50 Hz)";
        }
        last_mag = sensors;
        ++mags;
      }
      if (baro) {
        if (baros > 1) {
          EXPECT_EQ(sensors - last_baro, 25) << "baro every 25th HIL_SENSOR (10 Hz)";
        }
        last_baro = sensors;
        ++baros;
      }
      // At rest, level: specific force up, so z reads about -g in FRD.
      EXPECT_NEAR(s.zacc, -9.80665, 0.6);
      EXPECT_NEAR(s.xacc, 0.0, 0.6);
      if (mag) {
        EXPECT_NEAR(std::sqrt(s.xmag * s.xmag + s.ymag * s.ymag + s.zmag * s.zmag), 0.482, 0.03);
      }
      if (baro) {
        EXPECT_NEAR(s.abs_pressure, 955.6, 1.0);  // hPa: ISA at 488 m
        EXPECT_NEAR(s.pressure_alt, 488.2, 2.0);
      }
    } else if (f.is<msg::HilGps>()) {
      const auto g = f.as<msg::HilGps>();
      ++gps;
      EXPECT_EQ(g.fix_type, 3);
      EXPECT_GE(g.satellites_visible, 6);
      EXPECT_NEAR(g.lat, 473977420, 300);  // degE7, within a few metres
      EXPECT_NEAR(g.lon, 85455940, 500);
      EXPECT_NEAR(g.alt, 488000 + 230, 5000);  // mm MSL
      EXPECT_GT(g.eph, 0);
      EXPECT_LT(g.eph, 500);  // cm
      EXPECT_TRUE(g.cog == 65535 || g.cog < 36000) << g.cog;  // cdeg, or unknown when (noisily) standing still
    } else if (f.is<msg::Heartbeat>()) {
      ++heartbeats;
      EXPECT_EQ(f.as<msg::Heartbeat>().autopilot, 8);  // MAV_AUTOPILOT_INVALID: not a vehicle
    }
  }
  EXPECT_EQ(sensors, 500);  // 2 s of 4 ms steps
  EXPECT_EQ(mags, 101);     // 50 Hz, the samples at t = 0 and t = 2 s both included
  EXPECT_EQ(baros, 21);     // 10 Hz
  EXPECT_NEAR(gps, 61, 1);  // 30 Hz on absolute due times
  EXPECT_EQ(heartbeats, 3); // 1 Hz of simulated time: 0, 1, 2 s

  const auto odo = vio.receive_for(300ms);
  ASSERT_FALSE(odo.empty());
  EXPECT_EQ(odo.back().compid, 197);  // MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY, its own sequence
  const auto o = odo.back().as<msg::Odometry>();
  EXPECT_EQ(o.frame_id, 1);
  EXPECT_EQ(o.child_frame_id, 12);
  EXPECT_NEAR(o.q[0] * o.q[0] + o.q[1] * o.q[1] + o.q[2] * o.q[2] + o.q[3] * o.q[3], 1.0, 1e-5);
  EXPECT_NEAR(o.z, -0.23, 0.05);  // resting on the gear, NED z up is negative
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["type"], "summary");
  EXPECT_EQ(j["end"], "duration");
  EXPECT_NEAR(j["sim_time_s"].get<double>(), 2.0, 1e-6);
  EXPECT_EQ(j["sent"]["HIL_SENSOR"]["count"], 500);
}

TEST(SimE2E, RatesAtRealTimeMeasuredWithInspect) {
  const uint16_t board_port = test::free_udp_port();
  Process inspect({test::hitl_binary(), "inspect", "--port", std::to_string(board_port), "--bind", "127.0.0.1",
                   "--duration", "2", "--json", "--expect", "HIL_SENSOR=250,HIL_GPS=30"});
  ASSERT_TRUE(inspect.wait_for_stderr("listening", 10s));
  Process sim({test::hitl_binary(), "sim", "--hil-port", std::to_string(board_port), "--local-port",
               std::to_string(test::free_udp_port()), "--no-vio", "--clients", "0", "--duration", "4"});
  EXPECT_EQ(inspect.wait(30s), 0) << inspect.out();
  EXPECT_EQ(sim.wait(30s), 0) << sim.err();
  const auto j = last_json(inspect.out());
  EXPECT_EQ(j["sources"][0]["lost"], 0);
  EXPECT_EQ(j["crc_errors"], 0);
}

double run_with_constant_command(double u, bool armed, double duration_s) {
  Board board;
  board.serve([&](const msg::HilSensor&, uint64_t) { return actuators(u, armed); });
  Process sim(board.sim_args({"--duration", std::to_string(duration_s), "--speed", "0", "--lockstep", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["lockstep"]["fallbacks"], 0);
  EXPECT_EQ(j["armed"], armed);
  return j["altitude_m"].get<double>();
}

TEST(SimE2E, HoverCommandHoldsMoreLiftsDisarmedStays) {
  const double rest = run_with_constant_command(0.0, false, 1.0);
  EXPECT_NEAR(rest, 0.0, 0.05);  // altitude above home at rest (issue 18: one definition)
  // Just under hover thrust it stays on its gear. (At exactly hover thrust it is weightless, and the
  // legs' 5 mm static compression pushes it off at a few cm/s.)
  EXPECT_NEAR(run_with_constant_command(kHover * 0.98, true, 4.0), rest, 0.02);
  EXPECT_GT(run_with_constant_command(kHover * 1.1, true, 3.0), rest + 2.0);
  EXPECT_NEAR(run_with_constant_command(1.0, false, 2.0), rest, 0.02);  // full command but disarmed: motors stopped
}

TEST(SimE2E, MotorsStopWhenActuatorsTimeOut) {
  Board board;
  const auto start = std::chrono::steady_clock::now();
  board.serve([&](const msg::HilSensor&, uint64_t) -> std::optional<msg::HilActuatorControls> {
    if (std::chrono::steady_clock::now() - start > 1200ms) return std::nullopt;  // the board goes silent
    return actuators(kHover * 1.15, true);
  });
  Process sim(board.sim_args({"--duration", "4", "--actuator-timeout", "0.3", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["actuator_timeouts"], 1);
  EXPECT_LT(j["altitude_m"].get<double>(), 0.3);  // climbed, then fell back to the ground
  EXPECT_GT(j["received"]["HIL_ACTUATOR_CONTROLS"]["count"].get<int>(), 100);
}

TEST(SimE2E, BadControlsAreClampedAndCounted) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    auto a = actuators(0.5, true);
    if (i % 4 == 1) a.controls[0] = std::nanf("");
    if (i % 4 == 2) a.controls[1] = INFINITY;
    if (i % 4 == 3) a.controls[2] = 7.0f;
    return a;
  });
  Process sim(board.sim_args({"--duration", "1", "--speed", "0", "--lockstep", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  const int received = j["received"]["HIL_ACTUATOR_CONTROLS"]["count"];
  EXPECT_GT(received, 200);
  EXPECT_NEAR(j["clamped"].get<int>(), received * 3 / 4, 2);
  EXPECT_TRUE(std::isfinite(j["altitude_m"].get<double>()));
}

TEST(SimE2E, OtherSendersAndOtherSystemsAreIgnored) {
  Board board;
  test::MavlinkPeer intruder(0, board.sim_port(), 1, 1);  // right sysid, wrong address
  board.serve([&](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    intruder.send(actuators(1.0, true));
    if (i >= 10 && i % 2 == 0) {  // the board's sysid 1 answered first and is locked
      auto enc = mavlink::FrameEncoder(7, 1);  // another system from the board's own address
      mavlink::FrameBuffer buf;
      board.peer().send_bytes({buf.data(), enc.encode(actuators(1.0, true), buf)});
      return std::nullopt;
    }
    return actuators(0.0, false);  // the board itself: disarmed
  });
  Process sim(board.sim_args({"--duration", "2", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_GT(j["ignored"]["other_address"].get<int>(), 100);
  EXPECT_GT(j["ignored"]["other_sysid"].get<int>(), 100);
  EXPECT_FALSE(j["armed"].get<bool>());
  EXPECT_NEAR(j["altitude_m"].get<double>(), 0.0, 0.05);  // on the ground: 0, as everywhere else (issue 18)
}

TEST(SimE2E, LockstepStepsOnlyOnAnswersAndFallsBackWhenTheyStop) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    if (i >= 300) return std::nullopt;  // stops answering after 300 steps
    return actuators(0.0, true);
  });
  Process sim(board.sim_args({"--duration", "1.6", "--speed", "0", "--lockstep", "--lockstep-timeout", "0.02", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  // Each of the board's 300 answers, less those to the free run before its first one, ended a wait.
  EXPECT_GE(j["lockstep"]["waits"].get<int>(), 50);
  // One wait runs out; then the session steps on without waiting until the board is heard again.
  EXPECT_EQ(j["lockstep"]["fallbacks"].get<int>(), 1);
  EXPECT_NE(sim.err().find("lockstep: no HIL_ACTUATOR_CONTROLS"), std::string::npos) << sim.err();
  EXPECT_NE(sim.err().find("stepping on without waiting"), std::string::npos) << sim.err();
}

/// Answers HIL_SENSORs in lockstep, stamping each answer with the HIL_SENSOR's time_usec as PX4
/// SITL does, but first repeats its answer to the previous one (late) and answers only 3 ms later.
/// Counts the HIL_SENSORs that arrived before it answered: the simulator stepped on without the
/// answer (on the late repeat).
struct DoubleAnsweringBoard {
  uint64_t answered = 0, early = 0;
  void run(Board& board, const std::atomic<bool>& stop) {
    auto set = mavlink::MessageSet::compiled();
    mavlink::FrameParser parser(set);
    std::deque<uint64_t> pending;
    auto drain = [&] {
      bool newer = false;
      while (auto d = board.peer().endpoint().receive())
        parser.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
          if (!f.is<msg::HilSensor>()) return;
          pending.push_back(f.as<msg::HilSensor>().time_usec);
          newer = true;
        });
      return newer;
    };
    uint64_t previous = 0;
    const auto until = std::chrono::steady_clock::now() + 60s;
    while (!stop.load() && std::chrono::steady_clock::now() < until) {
      if (pending.empty()) {
        if (board.peer().endpoint().wait_readable(20)) drain();
        continue;
      }
      const uint64_t t = pending.back();  // a backlog (the free run before the first answer): the newest only
      pending.clear();
      if (previous != 0) {
        auto late = actuators(0.0, true);
        late.time_usec = previous;
        board.peer().send(late);
      }
      std::this_thread::sleep_for(3ms);
      // A newer HIL_SENSOR here before the answer went out: the simulator stepped without it (on
      // the late repeat). (The first answers end the free run it makes until it hears the board.)
      if (drain() && answered > 10) ++early;
      auto a = actuators(0.0, true);
      a.time_usec = t;
      board.peer().send(a);
      ++answered;
      previous = t;
    }
  }
};

TEST(SimE2E, LateSecondAnswersNeverAdvanceLockstepEarly) {
  Board board;
  DoubleAnsweringBoard scripted;
  std::atomic<bool> stop{false};
  std::thread player([&] { scripted.run(board, stop); });
  Process sim(board.sim_args({"--duration", "3", "--speed", "0", "--lockstep", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  stop = true;
  player.join();
  const auto j = last_json(sim.out());
  EXPECT_GE(scripted.answered, 100u);
  // A HIL_SENSOR already waiting when the board answers went out before the answer: stepped early.
  EXPECT_LE(scripted.early, scripted.answered / 50) << scripted.early << " of " << scripted.answered;
  EXPECT_GE(j["lockstep"]["late_answers"].get<uint64_t>() + 10, scripted.answered);
  EXPECT_EQ(j["lockstep"]["fallbacks"], 0);
  EXPECT_EQ(j["lockstep"]["foreign_clock"], 0);
}

TEST(SimE2E, LockstepAgainstADeadBoardEndsOnTimeThenGivesUp) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    if (i >= 50) return std::nullopt;  // the board dies
    return actuators(0.0, false);
  });
  // --duration bounds the wall time: one wait runs out, then the session steps on in real time.
  const auto start = std::chrono::steady_clock::now();
  Process sim(board.sim_args({"--duration", "4", "--lockstep", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  EXPECT_LT(std::chrono::steady_clock::now() - start, 20s);
  EXPECT_EQ(last_json(sim.out())["end"], "duration");
  board.stop();

  // Longer than the give-up time (10 s of silence): the session ends, says what to restart, exit 1.
  Board dead;
  dead.serve([](const msg::HilSensor&, uint64_t i) -> std::optional<msg::HilActuatorControls> {
    if (i >= 50) return std::nullopt;
    return actuators(0.0, false);
  });
  Process gone(dead.sim_args({"--duration", "60", "--lockstep", "--no-vio"}));
  EXPECT_EQ(gone.wait(60s), 1) << gone.err();
  EXPECT_NE(gone.err().find("ending the session"), std::string::npos) << gone.err();
  EXPECT_NE(gone.err().find("restart"), std::string::npos) << gone.err();
  const auto j = last_json(gone.out());
  EXPECT_EQ(j["end"], "flight_stack_gone");
  EXPECT_LT(j["sim_time_s"].get<double>(), 30.0);
}

TEST(SimE2E, ImuSamplesBeyondFullScaleAreClippedCountedAndSaid) {
  // An IMU whose accel range (0.5 g) is below gravity: every sample at rest clips on z.
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/small_imu.json") << R"({"sensors": {"imu": {"accel_range_m_s2": 4.9}}})";
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "1", "--speed", "0", "--no-vio", "--vehicle", dir + "/small_imu.json"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  board.stop();
  for (const auto& f : board.frames()) {
    if (f.is<msg::HilSensor>()) {
      EXPECT_LE(std::abs(f.as<msg::HilSensor>().zacc), 4.9f);
    }
  }
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["imu_saturated"]["accel"], 250);
  EXPECT_EQ(j["imu_saturated"]["gyro"], 0);
  EXPECT_NE(sim.err().find("IMU at full scale"), std::string::npos) << sim.err();
  EXPECT_EQ(j["landing"]["touchdowns"], 0);
}

TEST(SimE2E, WarnsOnceWhenTheBoardNeverAnswers) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "3", "--no-vio"}));
  EXPECT_EQ(sim.wait(60s), 0);
  const auto err = sim.err();
  EXPECT_NE(err.find("no HIL_ACTUATOR_CONTROLS"), std::string::npos) << err;
  EXPECT_NE(err.find("locked to an earlier session's port"), std::string::npos);
  EXPECT_EQ(err.find("no HIL_ACTUATOR_CONTROLS"), err.rfind("no HIL_ACTUATOR_CONTROLS"));  // once
}

TEST(SimE2E, BadInputExitsTwoWithAClearLine) {
  test::MavlinkPeer holder(0, 0);
  auto in_use = test::run_hitl({"sim", "--bind", "127.0.0.1", "--local-port", std::to_string(holder.endpoint().local_address().port()), "--clients", "0"});
  EXPECT_EQ(in_use.exit_code, 2);
  EXPECT_NE(in_use.err.find("already in use"), std::string::npos) << in_use.err;
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/v.json") << R"({"rotors": [{"time_constant_up_s": -1}]})";
  auto bad = test::run_hitl({"sim", "--vehicle", dir + "/v.json", "--clients", "0"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("time_constant_up_s"), std::string::npos) << bad.err;
  EXPECT_EQ(test::run_hitl({"sim", "--px4-sitl", "ftp:1"}).exit_code, 2);
  // The same port for the clients and the HIL link's local port: say so, not "another process".
  const auto same = std::to_string(test::free_udp_port());
  auto clash = test::run_hitl({"sim", "--bind", "127.0.0.1", "--local-port", same, "--clients", same, "--duration", "1"});
  EXPECT_EQ(clash.exit_code, 2);
  EXPECT_NE(clash.err.find("--clients " + same + " is also the --local-port"), std::string::npos) << clash.err;
  EXPECT_EQ(test::run_hitl({"sim", "--speed", "-1"}).exit_code, 2);
  // A number too large for a double (1e400) in a JSON file aborted the process (SIGABRT, an
  // uncaught nlohmann out_of_range) instead of a named error.
  std::ofstream(dir + "/big.json") << R"({"sensors": {"imu": {"accel_range_m_s2": 1e400}}})";
  std::ofstream(dir + "/bigw.json") << R"({"home": {"lat_deg": 1e400}})";
  std::ofstream(dir + "/bigt.json") << R"({"waypoints": [{"t": 0, "x": 1e400, "y": 0, "z": 2, "yaw": 0}]})";
  for (const auto& args : std::vector<std::vector<std::string>>{{"sim", "--vehicle", dir + "/big.json", "--clients", "0"},
                                                                {"sim", "--world", dir + "/bigw.json", "--clients", "0"},
                                                                {"sim", "-t", dir + "/bigt.json", "--clients", "0"}}) {
    auto big = test::run_hitl(args);
    EXPECT_EQ(big.exit_code, 2) << args[2] << ": " << big.err;
    EXPECT_NE(big.err.find("1e400"), std::string::npos) << big.err;
    EXPECT_EQ(big.err.find("terminate called"), std::string::npos) << big.err;
  }
}

TEST(SimE2E, RecordWriteErrorIsSaidAtOnceAndExitsOne) {
  // Issue 19: `sim --record /dev/full` exited 0 with nothing written.
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "60", "--no-vio", "--record", "/dev/full"}));
  EXPECT_TRUE(sim.wait_for_stderr("writing '/dev/full' failed: No space left on device", 10s)) << sim.err();
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(30s), 1) << sim.err();
  EXPECT_EQ(last_json(sim.out())["record_error"], "writing '/dev/full' failed: No space left on device");
}

TEST(SimE2E, CtrlCEndsASlowMotionSessionAtOnce) {
  // At --speed 0.001 a 4 ms step is 4 s of wall time; Ctrl-C used to wait for the step's deadline
  // (at --speed 1e-9: never, the sleep restarting on each signal), with no summary.
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "60", "--no-vio", "--speed", "1e-6"}));
  ASSERT_TRUE(sim.wait_for_stderr("Ctrl-C to stop", 10s)) << sim.err();
  std::this_thread::sleep_for(300ms);
  const auto t0 = std::chrono::steady_clock::now();
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(5s), 0) << sim.err();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 1s);
  EXPECT_EQ(last_json(sim.out())["end"], "stopped") << sim.out();
}

TEST(SimE2E, NumberOptionsRefuseNanInfAndAbsurdValuesPlainly) {
  // Issue 19: --actuator-timeout nan disabled the motor-stop failsafe; --lockstep-timeout nan was taken.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--actuator-timeout", "nan"}, "--actuator-timeout: nan is not a finite number"},
      {{"--lockstep-timeout", "nan"}, "--lockstep-timeout: nan is not a finite number"},
      {{"--actuator-timeout", "inf"}, "--actuator-timeout: inf is not a finite number"},
      {{"--duration", "1e999"}, "--duration: 1e999 is not a finite number"},
      {{"--speed", "-1"}, "--speed: -1 is below 0"},
      {{"--truth-rate", "1e12"}, "--truth-rate: 1e12 is too large (at most 1e+09 in size)"},
      {{"--vio-rate", "0"}, "--vio-rate: 0 is not greater than 0"},
      {{"--seed", "-1"}, "--seed: -1 is negative; give 0 or more"},
  };
  for (const auto& [args, words] : cases) {
    std::vector<std::string> a{"sim", "--clients", "0"};
    a.insert(a.end(), args.begin(), args.end());
    const auto r = test::run_hitl(a, 20s);
    EXPECT_EQ(r.exit_code, 2) << args[0] << " " << args[1];
    EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("17976931348623157"), std::string::npos) << r.err;  // no DBL_MAX in words
  }
}

TEST(SimE2E, PhysicsStepPacesRealTimeOrIsRefusedSayingWhy) {
  // Issue 19: physics.step_s 0.002 gave RTF 0.50 and HIL_SENSOR at 125 Hz; 0.1 gave RTF 24.9.
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/coarse.json") << R"({"physics": {"step_s": 0.1, "max_substep_s": 0.004}})";
  auto coarse = test::run_hitl({"sim", "--world", dir + "/coarse.json", "--clients", "0"});
  EXPECT_EQ(coarse.exit_code, 2);
  EXPECT_NE(coarse.err.find("physics.step_s 0.1 does not divide the IMU period 0.004 s (250 Hz)"), std::string::npos)
      << coarse.err;
  std::ofstream(dir + "/fine.json") << R"({"physics": {"step_s": 0.002, "max_substep_s": 0.002}})";
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--duration", "2", "--no-vio", "--world", dir + "/fine.json"}));
  EXPECT_EQ(sim.wait(60s), 0) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["sent"]["HIL_SENSOR"]["count"].get<int>(), 500);  // 250 Hz of simulated time
  EXPECT_NEAR(j["real_time_factor"].get<double>(), 1.0, 0.1);  // paced by the 2 ms step: was 0.50
  EXPECT_GE(j["wall_time_s"].get<double>(), 1.8);
  // On the 4 ms grid as with the default step (4000, 8000, ...): the first used to go out after the
  // first 2 ms step, at 2000 us, 2 ms before the second.
  board.stop();
  std::vector<uint64_t> stamps;
  for (const auto& f : board.frames()) {
    if (f.is<msg::HilSensor>()) stamps.push_back(f.as<msg::HilSensor>().time_usec);
  }
  ASSERT_FALSE(stamps.empty());
  EXPECT_EQ(stamps.front(), 4000u);
  for (std::size_t i = 0; i < stamps.size(); ++i) EXPECT_EQ(stamps[i] % 4000, 0u) << "HIL_SENSOR " << i << " at " << stamps[i] << " us";
}

TEST(SimE2E, RoutesClientsToTheBoardAndTelemetryBack) {
  Board board;
  const uint16_t clients_port = test::free_udp_port();
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  auto args = board.sim_args({"--duration", "3", "--no-vio"});
  *(std::find(args.begin(), args.end(), "--clients") + 1) = std::to_string(clients_port);
  Process sim(args);
  std::this_thread::sleep_for(500ms);
  test::MavlinkPeer client(0, clients_port, 255, 190);
  msg::CommandLong cmd;
  cmd.command = 400;  // MAV_CMD_COMPONENT_ARM_DISARM
  cmd.param1 = 1;
  client.send(cmd);
  std::this_thread::sleep_for(300ms);
  bool board_got_command = false;
  for (const auto& f : board.frames()) board_got_command |= f.is<msg::CommandLong>() && f.sysid == 255;
  EXPECT_TRUE(board_got_command);
  board.peer().send(msg::Attitude{});
  const auto got = client.receive_for(500ms);
  bool client_got_attitude = false, client_got_hil = false;
  for (const auto& f : got) {
    client_got_attitude |= f.is<msg::Attitude>();
    client_got_hil |= f.is<msg::HilSensor>() || f.is<msg::HilGps>();
  }
  EXPECT_TRUE(client_got_attitude);
  EXPECT_FALSE(client_got_hil);
  EXPECT_EQ(sim.wait(30s), 0);
}

TEST(SimE2E, BarePx4SitlFlagServesTcp4560) {
  // The documented form, with no value: it must mean tcp:4560, not fall back to a board link.
  Process sim({test::hitl_binary(), "sim", "--px4-sitl", "--no-vio", "--clients", "0", "--bind", "127.0.0.1",
               "--duration", "0.1"});
  const bool serving = sim.wait_for_stderr("waiting for PX4 SITL to connect to TCP 127.0.0.1:4560", 10s) ||
                       sim.err().find("4560") != std::string::npos;  // or 4560 was taken: the error names it
  EXPECT_TRUE(serving) << sim.err();
  EXPECT_EQ(sim.err().find("HIL_SENSOR/HIL_GPS to"), std::string::npos) << sim.err();
  sim.signal(SIGINT);
  sim.wait(10s);
}

/// `hitl sim --px4-sitl tcp:PORT`, unpaced, waiting for PX4 to connect.
std::unique_ptr<Process> start_px4_sitl_session(uint16_t port) {
  auto sim = std::make_unique<Process>(std::vector<std::string>{
      test::hitl_binary(), "--json", "sim", "--px4-sitl", "tcp:" + std::to_string(port), "--no-vio", "--clients", "0",
      "--speed", "0", "--bind", "127.0.0.1"});
  EXPECT_TRUE(sim->wait_for_stderr("waiting for PX4 SITL", 10s)) << sim->err();
  return sim;
}

/// Connects to the session as PX4 SITL's simulator_mavlink does; -1 when it cannot.
int connect_as_px4_sitl(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) return fd;
  ::close(fd);
  return -1;
}

/// Plays PX4 SITL's simulator_mavlink: connects to hitl over TCP, answers in lockstep.
TEST(SimE2E, Px4SitlOverTcpLockstepOnTheSimulatorsClock) {
  const uint16_t port = test::free_udp_port();  // a free number; TCP on the same number is very likely free too
  auto session = start_px4_sitl_session(port);
  Process& sim = *session;
  const int fd = connect_as_px4_sitl(port);
  ASSERT_GE(fd, 0);
  auto set = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(set);
  mavlink::FrameEncoder px4(1, 1);
  uint64_t sensors = 0, last_t = 0;
  bool monotonic = true;
  uint8_t buf[4096];
  while (sensors < 1000) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    ASSERT_GT(n, 0);
    parser.feed({buf, static_cast<std::size_t>(n)}, [&](const mavlink::Frame& f) {
      if (!f.is<msg::HilSensor>()) return;
      const auto s = f.as<msg::HilSensor>();
      monotonic &= s.time_usec > last_t;
      last_t = s.time_usec;
      ++sensors;
      if (sensors < 275) return;  // PX4 boots ~1.1 s of simulated time before it answers
      mavlink::FrameBuffer out;
      const std::size_t len = px4.encode(actuators(0.0, false), out);
      ASSERT_EQ(::send(fd, out.data(), len, MSG_NOSIGNAL), static_cast<ssize_t>(len));
    });
  }
  EXPECT_TRUE(monotonic);
  EXPECT_EQ(last_t, sensors * 4000);
  ::close(fd);  // PX4 exits: the session must end, saying why
  EXPECT_EQ(sim.wait(30s), 1);
  EXPECT_NE(sim.err().find("PX4 SITL disconnected"), std::string::npos) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["end"], "flight_stack_gone");
  // Answers to the HIL_SENSORs sent unpaced before PX4's first answer arrive together and one wait
  // takes them all, so the count of waits is below the 725 answers by a load-dependent amount.
  EXPECT_GE(j["lockstep"]["waits"].get<int>(), 200);
  EXPECT_EQ(j["lockstep"]["fallbacks"], 0);
}

/// PX4 SITL still on an earlier session's clock: its answers are stamped far ahead; the session
/// says so once, and what to restart.
TEST(SimE2E, Px4SitlOnAnEarlierSessionsClockIsSaid) {
  const uint16_t port = test::free_udp_port();
  auto session = start_px4_sitl_session(port);
  Process& sim = *session;
  const int fd = connect_as_px4_sitl(port);
  ASSERT_GE(fd, 0);
  auto set = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(set);
  mavlink::FrameEncoder px4(1, 1);
  uint64_t sensors = 0;
  uint8_t buf[4096];
  while (sensors < 300) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    ASSERT_GT(n, 0);
    parser.feed({buf, static_cast<std::size_t>(n)}, [&](const mavlink::Frame& f) {
      if (!f.is<msg::HilSensor>()) return;
      ++sensors;
      auto a = actuators(0.0, false);
      a.time_usec = f.as<msg::HilSensor>().time_usec + 600000000;  // 10 minutes into an earlier session
      mavlink::FrameBuffer out;
      const std::size_t len = px4.encode(a, out);
      ASSERT_EQ(::send(fd, out.data(), len, MSG_NOSIGNAL), static_cast<ssize_t>(len));
    });
  }
  ::close(fd);
  EXPECT_EQ(sim.wait(30s), 1);
  EXPECT_NE(sim.err().find("still runs on an earlier session's time"), std::string::npos) << sim.err();
  EXPECT_NE(sim.err().find("Restart PX4 SITL together with hitl sim"), std::string::npos) << sim.err();
}

}  // namespace
}  // namespace hitl
