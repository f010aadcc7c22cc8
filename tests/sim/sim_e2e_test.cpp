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
#include <csignal>
#include <cmath>
#include <fstream>
#include <functional>
#include <thread>

#include "engine/mavlink/enums.h"
#include "engine/mavlink/frame_parser.h"
#include "engine/mavlink/hil_sensor_fields.h"
#include "engine/mavlink/messages.h"
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
  EXPECT_NEAR(run_with_constant_command(kHover, true, 4.0), rest, 0.1);  // weightless on its gear: neither climbs nor sinks
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
  EXPECT_GE(j["lockstep"]["waits"].get<int>(), 299);
  EXPECT_GE(j["lockstep"]["fallbacks"].get<int>(), 90);  // the last 100 steps waited in vain
  EXPECT_NE(sim.err().find("lockstep: no HIL_ACTUATOR_CONTROLS"), std::string::npos) << sim.err();
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
  EXPECT_EQ(test::run_hitl({"sim", "--speed", "-1"}).exit_code, 2);
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

/// Plays PX4 SITL's simulator_mavlink: connects to hitl over TCP, answers in lockstep.
TEST(SimE2E, Px4SitlOverTcpLockstepOnTheSimulatorsClock) {
  const uint16_t port = test::free_udp_port();  // a free number; TCP on the same number is very likely free too
  Process sim({test::hitl_binary(), "--json", "sim", "--px4-sitl", "tcp:" + std::to_string(port), "--no-vio", "--clients", "0",
               "--speed", "0", "--bind", "127.0.0.1"});
  ASSERT_TRUE(sim.wait_for_stderr("waiting for PX4 SITL", 10s)) << sim.err();
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
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
  EXPECT_GE(j["lockstep"]["waits"].get<int>(), 700);
  EXPECT_EQ(j["lockstep"]["fallbacks"], 0);
}

}  // namespace
}  // namespace hitl
