// Fixed dashboard models for the drawing tests: every panel filled with known values.
#pragma once

#include <cmath>

#include "tui/dashboard_model.h"

namespace hitl::tui::test {

inline PathRow path(const char* name, const char* message, double expected_hz, double rate_hz, Health health) {
  PathRow r;
  r.name = name;
  r.message = message;
  r.expected_hz = expected_hz;
  r.rate_hz = rate_hz;
  r.jitter_ms = 0.05;
  r.max_gap_ms = 4.6;
  r.count = 12345;
  r.health = health;
  return r;
}

inline DashboardModel sample_model() {
  DashboardModel m;
  m.title = "hitl sim";
  m.state = "running";
  m.clock = "sim 12.3 s  rtf 1.00";
  m.keys = "adtlprfs";
  m.paths.caption = "expected at --speed 1; loss: frames from the board";
  m.paths.rows = {path("IMU", "HIL_SENSOR", 250, 249.0, Health::Good), path("mag", "HIL_SENSOR", 50, 45.0, Health::Degraded),
                  path("baro", "HIL_SENSOR", 10, 5.0, Health::Bad),   path("GPS", "HIL_GPS", 30, 30.0, Health::Good),
                  path("ODOMETRY", "ODOMETRY", 250, 250.0, Health::Good),
                  path("actuators", "HIL_ACTUATOR_CONTROLS", 250, 248.0, Health::Good)};
  m.paths.rows.back().outgoing = false;
  m.paths.rows.back().loss_pct = 0.0;

  DspHitlPanel d;
  d.running = true;
  d.age_s = 0.4;
  const char* names[] = {"HIL sensor_imu received", "IMU updates published", "HIL sensor_mag_baro received",
                         "MAG updates published", "BARO updates published"};
  const char* shorts[] = {"sensor_imu", "IMU pub", "mag_baro", "MAG pub", "BARO pub"};
  const double rates[] = {249.5, 249.5, 100.0, 50.0, 0.0};
  const double expected[] = {250, 250, 100, 50, 10};
  for (int i = 0; i < 5; ++i) {
    CounterRow c;
    c.name = names[i];
    c.short_name = shorts[i];
    c.count = 1000u * static_cast<unsigned>(i + 1);
    c.rate_hz = rates[i];
    c.expected_hz = expected[i];
    c.stalled = i == 4;  // BARO stopped
    c.health = i == 4 ? Health::Bad : Health::Good;
    d.counters.push_back(c);
  }
  m.dsp_hitl = d;

  EkfPanel e;
  e.flags = telemetry::estimator_flags(0x003F | 0x0400);  // attitude .. pos vert abs, and a GPS glitch
  e.ratios = {{"vel", 0.2}, {"pos h", 0.7}, {"pos v", 1.3}, {"mag", 0.1}};
  e.horizontal_error_m = 0.12;
  e.vertical_error_m = -0.03;
  e.attitude_error_deg = 0.4;
  e.horizontal_rms_m = 0.10;
  e.attitude_rms_deg = 0.3;
  e.horizontal_accuracy_m = 0.5;
  e.vertical_accuracy_m = 0.8;
  m.ekf = e;

  VehiclePanel v;
  v.armed = true;
  v.mode = "Position";
  v.landed = "in air";
  v.in_air = true;
  v.ready_to_arm = true;
  v.battery_V = 16.8;
  v.battery_A = 5.0;
  v.battery_pct = 100;
  v.altitude_m = 2.48;
  v.truth_altitude_m = 2.50;
  v.motors = std::array<double, 4>{0.5, 0.25, 1.0, 0.0};
  v.rotor_speed_rad_s = std::array<double, 4>{500, 250, 1000, 0};
  v.rotor_max_rad_s = 1000;
  m.vehicle = v;

  for (int i = 0; i < 8; ++i) m.messages.push_back({1.0 * i, Severity::Info, "line " + std::to_string(i)});
  m.messages.push_back({9.0, Severity::Error, "Preflight Fail: ekf2 not aligned"});
  m.link_partner = "127.0.0.1:14560";
  m.link = {{"rtf", "1.00"}, {"late", "3", Health::Degraded}, {"out", "1000"}, {"in", "900"}, {"ignored", "0"},
            {"clamped", "0"}, {"crc err", "0"}, {"lockstep", "0 fb"}, {"rtf total", "0.99"}, {"max late", "1.2 ms"}};
  return m;
}

}  // namespace hitl::tui::test
