// hitl sim end to end, what the simulator sends the board: HIL_SENSOR with its exact fields_updated
// cadence, frames and units, HIL_GPS, HEARTBEAT and VIO odometry; the rates at real time; IMU
// samples clipped at full scale; a physics step that paces real time on the 4 ms grid or is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <thread>

#include "base/mavlink/hil_sensor_fields.h"
#include "tests/cli/sim_board.h"

namespace hitl {
namespace {

using namespace sim_e2e;

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

}  // namespace
}  // namespace hitl
