// The session's parts on their own: ActuatorInput (clamp, sysid lock, timeout stop), Pacer
// (absolute deadlines), make_hil_sensor / make_hil_gps (fields_updated, wire units).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "base/common/clock.h"
#include "engine/hil/actuator_input.h"
#include "engine/hil/pacer.h"
#include "engine/hil/sensor_messages.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/hil_sensor_fields.h"

namespace hitl::hil {
namespace {

mavlink::msg::HilActuatorControls controls(float u0, float u1, float u2, float u3, bool armed = true) {
  mavlink::msg::HilActuatorControls m;
  m.controls = {};
  m.controls[0] = u0;
  m.controls[1] = u1;
  m.controls[2] = u2;
  m.controls[3] = u3;
  m.mode = armed ? mavlink::mode_flag::kSafetyArmed : 0;
  return m;
}

// --- ActuatorInput -------------------------------------------------------------------------------

TEST(ActuatorInput, ClampsNonFiniteAndOutOfRangeControlsAndCountsEachMessageOnce) {
  ActuatorInput in(0.5);
  EXPECT_TRUE(in.on_message(controls(0.25f, 0.5f, 0.75f, 1.0f), 1, 0.0));
  EXPECT_EQ(in.counters().clamped, 0u);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(in.on_message(controls(nan, 1.5f, -0.2f, inf), 1, 0.01));
  EXPECT_EQ(in.counters().clamped, 1u);
  const auto c = in.commands(0.02);
  EXPECT_DOUBLE_EQ(c.u[0], 0.0);  // NaN: stopped, not full throttle
  EXPECT_DOUBLE_EQ(c.u[1], 1.0);
  EXPECT_DOUBLE_EQ(c.u[2], 0.0);
  EXPECT_DOUBLE_EQ(c.u[3], 0.0);  // inf is not finite: 0
  EXPECT_TRUE(c.armed);
}

TEST(ActuatorInput, LocksOntoTheFirstSysidAndIgnoresOthers) {
  ActuatorInput in(0.5);
  EXPECT_TRUE(in.on_message(controls(0.4f, 0.4f, 0.4f, 0.4f), 1, 0.0));
  EXPECT_FALSE(in.on_message(controls(0.9f, 0.9f, 0.9f, 0.9f), 2, 0.001));
  EXPECT_EQ(in.counters().ignored_sysid, 1u);
  EXPECT_EQ(in.locked_sysid(), std::optional<uint8_t>(1));
  EXPECT_FLOAT_EQ(static_cast<float>(in.commands(0.002).u[0]), 0.4f);  // the other system's controls never fly
  EXPECT_EQ(in.counters().received, 1u);
}

TEST(ActuatorInput, StopsTheMotorsAfterTheTimeoutAndCountsEachTimeoutOnce) {
  ActuatorInput in(0.5);
  EXPECT_FALSE(in.commands(0.0).armed);  // nothing heard yet: stopped, but no timeout counted
  EXPECT_EQ(in.counters().timeouts, 0u);
  in.on_message(controls(0.6f, 0.6f, 0.6f, 0.6f), 1, 1.0);
  EXPECT_TRUE(in.commands(1.4).armed);
  EXPECT_DOUBLE_EQ(in.commands(1.4).u[0], 0.6f);
  const auto stopped = in.commands(1.51);
  EXPECT_FALSE(stopped.armed);
  for (double u : stopped.u) EXPECT_DOUBLE_EQ(u, 0.0);
  (void)in.commands(1.6);
  EXPECT_EQ(in.counters().timeouts, 1u);  // one outage, one count
  in.on_message(controls(0.6f, 0.6f, 0.6f, 0.6f), 1, 2.0);
  EXPECT_TRUE(in.commands(2.1).armed);  // the stream is back: flying again
  (void)in.commands(3.0);
  EXPECT_EQ(in.counters().timeouts, 2u);
}

// --- Pacer ---------------------------------------------------------------------------------------

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

TEST(Pacer, KeepsAbsoluteDeadlinesSoWorkInEachTickDoesNotAddUp) {
  // 20 ticks of 20 ms with 8 ms of work in each: on absolute deadlines the run takes 20 x 20 ms;
  // sleeping a period after each tick's work would take 20 x 28 ms.
  Pacer pacer(0.020, 1.0);
  pacer.start();
  const double t0 = now_s();
  for (int k = 0; k < 20; ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(8));
    pacer.wait_next();
  }
  const double elapsed_s = now_s() - t0;
  EXPECT_GE(elapsed_s, 0.400 - 0.002);
  EXPECT_LT(elapsed_s, 0.480);
  EXPECT_EQ(pacer.stats().ticks, 20u);
}

TEST(Pacer, CountsALateTickAndCatchesUpBackToBack) {
  Pacer pacer(0.010, 1.0);
  pacer.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(35));  // 3.5 periods behind tick 1's deadline
  pacer.wait_next();
  EXPECT_EQ(pacer.stats().late, 1u);
  EXPECT_GT(pacer.stats().max_lateness_s, 0.010);
  EXPECT_EQ(pacer.stats().resyncs, 0u);  // within the catch-up window: no re-anchoring
  const double t0 = now_s();
  pacer.wait_next();  // tick 2 is already due: no sleep
  EXPECT_LT(now_s() - t0, 0.005);
}

TEST(Pacer, ReanchorsAfterAStallLongerThanTheCatchUpWindow) {
  Pacer pacer(0.004, 1.0);
  pacer.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  pacer.wait_next();
  EXPECT_EQ(pacer.stats().resyncs, 1u);
  const double t0 = now_s();
  pacer.wait_next();  // re-anchored: the next tick is one period away, not already due
  EXPECT_GT(now_s() - t0, 0.002);
}

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

TEST(Pacer, SpinsTheLastPartOfEachWaitAndNeverReturnsBeforeTheDeadline) {
  // 20 ticks of 4 ms, the last 2 ms of each spent spinning: never early, and the spin shows as
  // this thread's CPU time (a sleeping wait has next to none).
  auto cpu_of = [](double spin_s) {
    Pacer pacer(0.004, 1.0, spin_s);
    pacer.start();
    const double cpu0 = thread_cpu_s();
    for (int k = 0; k < 20; ++k) {
      const double due_s = pacer.next_due_s();
      pacer.wait_next();
      EXPECT_GE(hitl::monotonic_s(), due_s - 1e-7) << "tick " << k;
    }
    return thread_cpu_s() - cpu0;
  };
  const double sleeping_s = cpu_of(0.0);
  const double spinning_s = cpu_of(0.002);
  EXPECT_GT(spinning_s, sleeping_s + 0.005) << "sleeping " << sleeping_s << " s, spinning " << spinning_s << " s";
}

TEST(Pacer, SpeedZeroNeverSleeps) {
  Pacer pacer(1.0, 0.0);
  pacer.start();
  const double t0 = now_s();
  for (int k = 0; k < 100; ++k) pacer.wait_next();
  EXPECT_LT(now_s() - t0, 0.05);
  EXPECT_EQ(pacer.stats().late, 0u);
}

// --- make_hil_sensor / make_hil_gps -----------------------------------------------------------------

sensors::SensorFrame frame_with(bool imu, bool mag, bool baro) {
  sensors::SensorFrame f;
  if (imu) f.imu = sensors::ImuSample{0.004, {0.1, -0.2, -9.81}, {0.01, 0.02, -0.03}, 31.0};
  if (mag) f.mag = sensors::MagSample{0.004, {0.21, 0.01, 0.42}};
  if (baro) f.baro = sensors::BaroSample{0.004, 101325.0, 15.0, 12.5};
  return f;
}

TEST(MakeHilSensor, FieldsUpdatedNamesExactlyWhatWasSampled) {
  namespace bits = mavlink::hil_sensor;
  EXPECT_EQ(make_hil_sensor(frame_with(true, false, false), 4000).fields_updated, 0x3Fu);
  EXPECT_EQ(make_hil_sensor(frame_with(false, true, false), 4000).fields_updated, 0x1C0u);
  EXPECT_EQ(make_hil_sensor(frame_with(false, false, true), 4000).fields_updated, 0x1A00u);
  EXPECT_EQ(make_hil_sensor(frame_with(true, true, true), 4000).fields_updated,
            static_cast<uint32_t>(bits::kAccel | bits::kGyro | bits::kMag | bits::kBaro));
  EXPECT_EQ(make_hil_sensor(frame_with(true, true, true), 4000).fields_updated, 0x1BFFu);
}

TEST(MakeHilSensor, CarriesBodyFrdSiValuesAndPressureInHectopascal) {
  const auto m = make_hil_sensor(frame_with(true, true, true), 8000);
  EXPECT_EQ(m.time_usec, 8000u);
  EXPECT_FLOAT_EQ(m.zacc, -9.81f);  // specific force, FRD: level at rest reads -g on z
  EXPECT_FLOAT_EQ(m.yacc, -0.2f);
  EXPECT_FLOAT_EQ(m.zgyro, -0.03f);
  EXPECT_FLOAT_EQ(m.zmag, 0.42f);   // gauss
  EXPECT_FLOAT_EQ(m.abs_pressure, 1013.25f);  // Pa -> hPa
  EXPECT_FLOAT_EQ(m.pressure_alt, 12.5f);
  EXPECT_FLOAT_EQ(m.temperature, 15.0f);      // the baro's temperature when both were sampled
}

TEST(MakeHilGps, ConvertsToWireUnits) {
  sensors::GpsSample g;
  g.lat_deg = 47.3977419;
  g.lon_deg = 8.5455938;
  g.alt_m = 488.25;
  g.v_NED_m_s = {1.5, -2.25, 0.5};
  g.ground_speed_m_s = 2.7;
  g.course_over_ground_deg = 303.7;
  g.eph_m = 0.4;
  g.epv_m = 0.8;
  g.satellites = 12;
  const auto m = make_hil_gps(g, 12000);
  EXPECT_EQ(m.time_usec, 12000u);
  EXPECT_EQ(m.lat, 473977419);  // degE7
  EXPECT_EQ(m.lon, 85455938);
  EXPECT_EQ(m.alt, 488250);     // mm
  EXPECT_EQ(m.eph, 40);         // cm
  EXPECT_EQ(m.epv, 80);
  EXPECT_EQ(m.vel, 270);        // cm/s
  EXPECT_EQ(m.vn, 150);
  EXPECT_EQ(m.ve, -225);
  EXPECT_EQ(m.vd, 50);
  EXPECT_EQ(m.cog, 30370);      // cdeg
  EXPECT_EQ(m.satellites_visible, 12);
  EXPECT_EQ(m.fix_type, 3);
}

TEST(MakeHilGps, CourseIsUnknownWhenStanding) {
  sensors::GpsSample g;
  g.ground_speed_m_s = kCogMinSpeed_m_s / 2;
  g.course_over_ground_deg = 90;
  EXPECT_EQ(make_hil_gps(g, 4000).cog, 65535);
}

}  // namespace
}  // namespace hitl::hil
