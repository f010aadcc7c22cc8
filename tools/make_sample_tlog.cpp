// Writes a synthetic .tlog of a HITL link as the spec describes it, for the README's
// demonstration of `hitl inspect` before the simulator exists: HIL_SENSOR at 250 Hz
// (IMU every message, mag every 5th, baro every 25th), HIL_GPS at 30 Hz, ODOMETRY at
// 250 Hz from the simulator; HIL_ACTUATOR_CONTROLS at 200 Hz and HEARTBEAT from the board.
// Arrival times carry a little jitter. The values are a vehicle at rest at PX4's default home.
//
//   make_sample_tlog OUT.tlog [SECONDS]
#include <cstdio>
#include <cstdlib>
#include <random>

#include "engine/mavlink/enums.h"
#include "engine/mavlink/frame_encoder.h"
#include "engine/mavlink/hil_sensor_fields.h"
#include "engine/mavlink/messages.h"
#include "engine/mavlink/tlog.h"

using namespace hitl::mavlink;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: make_sample_tlog OUT.tlog [SECONDS]\n");
    return 2;
  }
  const double seconds = argc > 2 ? std::atof(argv[2]) : 5.0;
  auto writer = TlogWriter::open(argv[1]);
  if (!writer) {
    std::fprintf(stderr, "make_sample_tlog: %s\n", writer.error().message.c_str());
    return 1;
  }
  FrameEncoder sim(1, 200);   // the simulator's link
  FrameEncoder board(1, 1);   // PX4 on the board
  std::mt19937 rng(1);
  std::normal_distribution<double> jitter_us(0.0, 20.0);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  const uint64_t start_us = 1'767'225'600'000'000ULL;  // 2026-01-01 00:00:00 UTC
  FrameBuffer buf;
  auto put = [&](uint64_t t_us, std::size_t n) { writer->write(start_us + t_us + static_cast<uint64_t>(std::max(0.0, 100 + jitter_us(rng))), {buf.data(), n}); };

  const uint64_t end_us = static_cast<uint64_t>(seconds * 1e6);
  uint64_t next_gps = 0;
  for (uint64_t t = 0, tick = 0; t < end_us; t += 4000, ++tick) {
    msg::HilSensor s;
    s.time_usec = t;
    s.xacc = 0.02f * noise(rng);
    s.yacc = 0.02f * noise(rng);
    s.zacc = -9.80665f + 0.02f * noise(rng);
    s.xgyro = 0.002f * noise(rng);
    s.ygyro = 0.002f * noise(rng);
    s.zgyro = 0.002f * noise(rng);
    s.fields_updated = hil_sensor::kAccel | hil_sensor::kGyro;
    if (tick % 5 == 0) {
      s.xmag = 0.21f;
      s.ymag = 0.01f;
      s.zmag = 0.43f;
      s.fields_updated |= hil_sensor::kMag;
    }
    if (tick % 25 == 0) {
      s.abs_pressure = 955.0f + 0.01f * noise(rng);
      s.pressure_alt = 488.0f;
      s.temperature = 11.8f;
      s.fields_updated |= hil_sensor::kBaro;
    }
    put(t, sim.encode(s, buf));

    msg::Odometry o;
    o.time_usec = t;
    o.frame_id = 1;        // MAV_FRAME_LOCAL_NED
    o.child_frame_id = 12;  // MAV_FRAME_BODY_FRD
    o.q = {1, 0, 0, 0};
    o.pose_covariance[0] = NAN;
    o.velocity_covariance[0] = NAN;
    o.quality = 100;
    put(t + 50, sim.encode(o, buf));

    if (t >= next_gps) {
      next_gps += 33333;
      msg::HilGps g;
      g.time_usec = t;
      g.fix_type = 3;
      g.lat = 473977420;
      g.lon = 85455940;
      g.alt = 488000;
      g.eph = 90;
      g.epv = 150;
      g.cog = 65535;
      g.satellites_visible = 10;
      put(t + 100, sim.encode(g, buf));
    }
    if (t % 5000 < 4000) {  // 200 Hz back from the board
      msg::HilActuatorControls a;
      a.time_usec = t;
      a.flags = 0x0F;
      a.mode = mode_flag::kCustomModeEnabled | mode_flag::kHilEnabled;
      put(t + 1500, board.encode(a, buf));
    }
    if (tick % 250 == 0) {
      msg::Heartbeat hb;
      hb.type = static_cast<uint8_t>(MavType::Quadrotor);
      hb.autopilot = static_cast<uint8_t>(MavAutopilot::Px4);
      hb.base_mode = 61;
      hb.system_status = static_cast<uint8_t>(MavState::Standby);
      hb.mavlink_version = kMavlinkVersion;
      put(t + 2000, board.encode(hb, buf));
    }
  }
  if (!writer->flush()) {
    std::fprintf(stderr, "make_sample_tlog: writing %s failed\n", argv[1]);
    return 1;
  }
  return 0;
}
