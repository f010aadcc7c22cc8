// The emulated board's parts that board.cpp's split made testable on their own: the telemetry
// builders (telemetry_messages.h), the HIL input conversions and the lockstep clock (hil_input.h).
#include <gtest/gtest.h>

#include <cmath>

#include "base/contract/data_rates.h"
#include "base/mavlink/enums.h"
#include "emulator/hil_input.h"
#include "emulator/telemetry_messages.h"

namespace hitl::target {
namespace {

namespace msg = mavlink::msg;

FlightState flying() {
  FlightState s;
  s.attitude_valid = s.local_valid = s.global_valid = s.home_set = true;
  s.lat_deg = 47.3977419;
  s.lon_deg = 8.5455938;
  s.alt_msl_m = 498.25;
  s.p_NED_m = {1.0, -2.0, -10.0};
  s.v_NED_m_s = {0.5, -0.25, -1.0};
  s.yaw_rad = -M_PI / 2;  // facing west
  return s;
}

TEST(TelemetryMessages, GlobalPositionIntInWireUnits) {
  const auto m = global_position_int(flying(), 1234);
  EXPECT_EQ(m.time_boot_ms, 1234u);
  EXPECT_EQ(m.lat, 473977419);
  EXPECT_EQ(m.lon, 85455938);
  EXPECT_EQ(m.alt, 498250);           // mm MSL
  EXPECT_EQ(m.relative_alt, 10000);   // mm above home: -z NED
  EXPECT_EQ(m.vx, 50);                // cm/s NED
  EXPECT_EQ(m.vy, -25);
  EXPECT_EQ(m.vz, -100);
  EXPECT_EQ(m.hdg, 27000);            // cdeg, 0..35999: west
}

TEST(TelemetryMessages, HeadingWrapsIntoZeroTo35999) {
  auto s = flying();
  s.yaw_rad = 0.0;
  EXPECT_EQ(global_position_int(s, 0).hdg, 0);
  s.yaw_rad = M_PI;
  EXPECT_EQ(global_position_int(s, 0).hdg, 18000);
  s.yaw_rad = -1e-9;  // just west of north
  EXPECT_EQ(global_position_int(s, 0).hdg, 0);
}

TEST(TelemetryMessages, SysStatusHealthFollowsTheEstimateAndThePrearmCheck) {
  namespace b = mavlink::sys_status;
  FlightState s;
  auto m = sys_status(s);
  EXPECT_NE(m.onboard_control_sensors_present & b::kAhrs, 0u);
  EXPECT_EQ(m.onboard_control_sensors_health & b::kAhrs, 0u);         // attitude not valid yet
  EXPECT_EQ(m.onboard_control_sensors_health & b::kPrearmCheck, 0u);  // not ready to arm
  s.attitude_valid = true;
  s.ready_to_arm = true;
  m = sys_status(s);
  EXPECT_NE(m.onboard_control_sensors_health & b::kAhrs, 0u);
  EXPECT_NE(m.onboard_control_sensors_health & b::kPrearmCheck, 0u);
  EXPECT_EQ(m.voltage_battery, 16800);
}

TEST(TelemetryMessages, BatteryIsAFull4SPackWithUnknownsMarked) {
  const auto m = battery_status();
  EXPECT_EQ(m.voltages[0] + m.voltages[1] + m.voltages[2] + m.voltages[3], 16800);
  EXPECT_EQ(m.voltages[4], UINT16_MAX);  // cells beyond the fourth: not present
  EXPECT_EQ(m.temperature, INT16_MAX);
  EXPECT_EQ(m.current_consumed, -1);
}

TEST(TelemetryMessages, AttitudeQuaternionAndLocalPositionCopyTheWireFrames) {
  auto s = flying();
  s.q_FRD_to_NED = {0.5, 0.5, 0.5, 0.5};
  s.w_FRD_rad_s = {0.1, 0.2, 0.3};
  const auto q = attitude_quaternion(s, 7);
  EXPECT_FLOAT_EQ(q.q1, 0.5f);
  EXPECT_FLOAT_EQ(q.yawspeed, 0.3f);
  const auto p = local_position_ned(s, 7);
  EXPECT_FLOAT_EQ(p.z, -10.0f);
  EXPECT_FLOAT_EQ(p.vy, -0.25f);
}

TEST(TelemetryMessages, EveryDefaultStreamIsKnownAndActuatorsAreNotDefault) {
  for (const auto& stream : default_stream_intervals()) {
    EXPECT_TRUE(stream_known(stream.msgid)) << stream.msgid;
    EXPECT_GT(stream.interval_us, 0);
    EXPECT_NE(stream.msgid, msg::HilActuatorControls::kId);
  }
  EXPECT_TRUE(stream_known(msg::HilActuatorControls::kId));  // requested or the HIL instance's own
  EXPECT_TRUE(stream_known(msg::AutopilotVersion::kId));
  EXPECT_FALSE(stream_known(msg::HilSensor::kId));
  EXPECT_EQ(default_stream_intervals()[0].msgid, msg::Heartbeat::kId);
  EXPECT_EQ(default_stream_intervals()[0].interval_us, 1000000);  // HEARTBEAT at 1 Hz
}

TEST(TelemetryMessages, AutopilotVersionSaysMavlink2AndPx4V116) {
  const auto m = autopilot_version();
  EXPECT_NE(m.capabilities & mavlink::capability::kMavlink2, 0u);
  EXPECT_EQ(m.flight_sw_version >> 16, (1u << 8) | 16u);
}

TEST(HilInput, HilSensorIsCopiedFieldByFieldInWireUnits) {
  msg::HilSensor m;
  m.time_usec = 123456;
  m.xacc = 0.1f; m.yacc = 0.2f; m.zacc = -9.81f;
  m.xgyro = 0.01f; m.ygyro = 0.02f; m.zgyro = 0.03f;
  m.xmag = 0.2f; m.ymag = 0.0f; m.zmag = 0.4f;
  m.abs_pressure = 1013.25f;
  m.temperature = 21.5f;
  m.fields_updated = 0x1FFF;
  m.id = 2;
  const auto in = hil_sensor_input(m);
  EXPECT_EQ(in.time_usec, 123456u);
  EXPECT_FLOAT_EQ(in.accel_FRD_m_s2[2], -9.81f);
  EXPECT_FLOAT_EQ(in.gyro_FRD_rad_s[1], 0.02f);
  EXPECT_FLOAT_EQ(in.mag_FRD_gauss[2], 0.4f);
  EXPECT_FLOAT_EQ(in.abs_pressure_hPa, 1013.25f);  // still hPa: the split converts
  EXPECT_FLOAT_EQ(in.temperature_degC, 21.5f);
  EXPECT_EQ(in.fields_updated, 0x1FFFu);
  EXPECT_EQ(in.id, 2);
}

TEST(HilInput, HilGpsIsCopiedFieldByFieldInWireUnits) {
  msg::HilGps m;
  m.time_usec = 5;
  m.fix_type = 3;
  m.lat = 473977419;
  m.lon = 85455938;
  m.alt = 488000;
  m.eph = 30;
  m.vn = -120;
  m.cog = 65535;
  m.satellites_visible = 12;
  const auto in = hil_gps_input(m);
  EXPECT_EQ(in.fix_type, 3);
  EXPECT_EQ(in.lat_degE7, 473977419);
  EXPECT_EQ(in.alt_mm, 488000);
  EXPECT_EQ(in.eph_cm, 30);
  EXPECT_EQ(in.vn_cm_s, -120);
  EXPECT_EQ(in.cog_cdeg, 65535);
  EXPECT_EQ(in.satellites_visible, 12);
}

TEST(LockstepClock, FollowsSensorTimeOneImuPeriodAheadFromWhereTheWallClockWas) {
  LockstepClock clock;
  EXPECT_FALSE(clock.started());
  // The first HIL_SENSOR arrives 2.5 s into the board's life, stamped 1 s.
  uint64_t now = clock.on_hil_sensor(1000000, 2500000);
  EXPECT_TRUE(clock.started());
  EXPECT_EQ(now, 2500000 + kHilImuPublishPeriod_us);
  EXPECT_EQ(clock.last_sensor_time_us(), 1000000u);
  now = clock.on_hil_sensor(1000000 + 4000, now);
  EXPECT_EQ(now, 2500000 + 4000 + kHilImuPublishPeriod_us);
  // A repeated stamp never moves the clock back.
  EXPECT_EQ(clock.on_hil_sensor(1000000 + 4000, now + 100), now + 100);
  EXPECT_FALSE(clock.take_new_session_text());
  EXPECT_EQ(clock.restarts(), 0u);
}

TEST(LockstepClock, ATimeThatGoesBackIsANewSimulatorSessionAndTheBoardCarriesOn) {
  LockstepClock clock;
  uint64_t now = clock.on_hil_sensor(0, 1000000);
  for (uint64_t t = 4000; t <= 400000; t += 4000) now = clock.on_hil_sensor(t, now);
  const uint64_t before = now;
  now = clock.on_hil_sensor(8000, now);  // a new simulator, starting again near 0
  EXPECT_EQ(clock.restarts(), 1u);
  EXPECT_EQ(now, before + kHilImuPublishPeriod_us);  // re-anchored where the board was
  const auto text = clock.take_new_session_text();
  ASSERT_TRUE(text);
  EXPECT_NE(text->find("went back from 400 ms to 8 ms"), std::string::npos) << *text;
  EXPECT_FALSE(clock.take_new_session_text());  // said once
  EXPECT_EQ(clock.on_hil_sensor(12000, now), before + 4000 + kHilImuPublishPeriod_us);
}

}  // namespace
}  // namespace hitl::target
