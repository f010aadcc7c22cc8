// The sensor faults the wire tests (sensor_faults_on_the_wire_test.cpp) leave out, as a board
// reads them off HIL_SENSOR and HIL_GPS: imu-clip, imu-vibration, mag-stuck, mag-scale,
// baro-stuck, baro-offset, gps-jump, gps-drift, gps-noise. The vehicle at rest on its gear (the
// lockstep stand-in board commands 0); each fault's window against the readings around it.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "engine/model/atmosphere.h"
#include "tests/engine/hil/lockstep_board.h"

namespace hitl::hil {
namespace {

namespace msg = mavlink::msg;
using test_lockstep::mean_over;
using test_lockstep::Seen;

constexpr uint32_t kAccelBits = 1 | 2 | 4;     // HIL_SENSOR_UPDATED_FLAGS XACC|YACC|ZACC
constexpr uint32_t kMagBits = 64 | 128 | 256;  // XMAG|YMAG|ZMAG
constexpr uint32_t kPressureBit = 512;         // ABS_PRESSURE

Seen at_rest(const std::vector<std::string>& faults, double duration_s, bool noise) {
  return test_lockstep::fly(faults, duration_s, [](uint64_t) { return 0.0; }, noise);
}

/// The HIL_SENSORs with these fields new (the magnetometer at 50 Hz, the barometer at 10 Hz).
std::map<uint64_t, msg::HilSensor> updated(const Seen& seen, uint32_t bits) {
  std::map<uint64_t, msg::HilSensor> out;
  for (const auto& [t_us, s] : seen.sensors)
    if ((s.fields_updated & bits) == bits) out[t_us] = s;
  return out;
}

bool in(uint64_t time_us, double from_s, double to_s) { return time_us + 1 > from_s * 1e6 && time_us + 1 < to_s * 1e6; }

TEST(SensorFaultsAtTheBoard, ImuClipHoldsTheAccelAtTheRangeAndVibrationShakesItAsSet) {
  const auto seen = at_rest({"imu-clip:5,0.1@0.5+0.3", "imu-vibration:3,10@1+0.4"}, 1.6, false);
  int clipped = 0, shaken = 0;
  const double rest_z = mean_over(seen.sensors, 0.2, 0.5, [](const msg::HilSensor& s) { return s.zacc; });
  EXPECT_NEAR(rest_z, -9.81, 0.05);
  for (const auto& [t_us, s] : seen.sensors) {
    if (!(s.fields_updated & kAccelBits)) continue;
    const double t_s = static_cast<double>(t_us) * 1e-6;
    if (in(t_us, 0.5, 0.8)) {
      EXPECT_FLOAT_EQ(s.zacc, -5.0f) << t_s;  // 1 g on the gear, clipped at 5 m/s^2
      ++clipped;
    } else if (in(t_us, 1.0, 1.4)) {
      const double phase_rad = 2 * M_PI * 10 * (t_s - 1.0);
      EXPECT_NEAR(s.xacc, 3 * std::cos(phase_rad), 1e-3) << t_s;
      EXPECT_NEAR(s.yacc, 3 * std::sin(phase_rad), 1e-3) << t_s;
      EXPECT_NEAR(s.zacc, rest_z, 1e-3) << t_s;
      ++shaken;
    } else if (t_s > 0.1) {
      EXPECT_NEAR(s.zacc, rest_z, 1e-3) << t_s;
      EXPECT_NEAR(s.xacc, 0, 1e-3) << t_s;
    }
  }
  EXPECT_EQ(clipped, 75);  // 0.3 s at 250 Hz
  EXPECT_EQ(shaken, 100);
}

/// Each reading in [from_s, to_s) equals the last one before from_s, which differs from the one before it (noise).
template <typename F>
void expect_stuck(const Seen& seen, uint32_t bits, double from_s, double to_s, F value) {
  std::optional<double> last, before_last;
  int stuck = 0;
  for (const auto& [t_us, s] : seen.sensors) {
    if ((s.fields_updated & bits) != bits) continue;
    if (in(t_us, 0, from_s)) before_last = last, last = value(s);
    if (!in(t_us, from_s, to_s) || !last) continue;
    EXPECT_EQ(value(s), *last) << "at " << static_cast<double>(t_us) * 1e-6 << " s";
    ++stuck;
  }
  ASSERT_TRUE(last && before_last);
  EXPECT_NE(*last, *before_last) << "noise on: a live reading changes";
  EXPECT_GT(stuck, 3);
}

TEST(SensorFaultsAtTheBoard, MagStuckRepeatsItsLastReadingMagScaleMultipliesIt) {
  const auto noisy = at_rest({"mag-stuck@0.5+0.5"}, 1.2, true);
  expect_stuck(noisy, kMagBits, 0.5, 1.0, [](const msg::HilSensor& s) { return static_cast<double>(s.xmag); });
  expect_stuck(noisy, kMagBits, 0.5, 1.0, [](const msg::HilSensor& s) { return static_cast<double>(s.zmag); });
  const auto scaled = updated(at_rest({"mag-scale:2@0.5"}, 1.0, false), kMagBits);
  for (auto axis : {&msg::HilSensor::xmag, &msg::HilSensor::ymag, &msg::HilSensor::zmag}) {
    const auto mag = [axis](const msg::HilSensor& s) { return static_cast<double>(s.*axis); };
    const double before = mean_over(scaled, 0.2, 0.5, mag), after = mean_over(scaled, 0.5, 1.0, mag);
    EXPECT_NEAR(after, 2 * before, 1e-4);
  }
}

TEST(SensorFaultsAtTheBoard, BaroStuckRepeatsItsLastReadingBaroOffsetStepsThePressure) {
  const auto noisy = at_rest({"baro-stuck@0.5+1"}, 1.8, true);
  expect_stuck(noisy, kPressureBit, 0.5, 1.5, [](const msg::HilSensor& s) { return static_cast<double>(s.abs_pressure); });
  expect_stuck(noisy, kPressureBit, 0.5, 1.5, [](const msg::HilSensor& s) { return static_cast<double>(s.pressure_alt); });
  const auto offset = at_rest({"baro-offset:100@1"}, 2.0, false);
  const auto baro = updated(offset, kPressureBit);
  const auto pressure_hPa = [](const msg::HilSensor& s) { return static_cast<double>(s.abs_pressure); };
  const auto alt_m = [](const msg::HilSensor& s) { return static_cast<double>(s.pressure_alt); };
  const double before_hPa = mean_over(baro, 0.3, 1.0, pressure_hPa), after_hPa = mean_over(baro, 1.0, 2.0, pressure_hPa);
  EXPECT_NEAR((after_hPa - before_hPa) * 100.0, 100.0, 0.5) << "+100 Pa";
  const auto atmosphere = model::default_world_config().atmosphere;
  const double expected_m = model::isa_altitude_m(atmosphere, after_hPa * 100) - model::isa_altitude_m(atmosphere, before_hPa * 100);
  EXPECT_NEAR(mean_over(baro, 1.0, 2.0, alt_m) - mean_over(baro, 0.3, 1.0, alt_m), expected_m, 0.05);
  EXPECT_LT(expected_m, -7.0);  // about 8 m lower
}

TEST(SensorFaultsAtTheBoard, GpsJumpMovesTheFixGpsDriftWalksItAwayWithItsVelocity) {
  const auto seen = at_rest({"gps-jump:100,-50@0.5+0.3", "gps-drift:2,-1@1"}, 1.6, false);
  const auto home = model::default_world_config().home;
  const double m_per_degE7_lat = 111180.0e-7, m_per_degE7_lon = 75330.0e-7;  // at 47.4 N
  std::optional<msg::HilGps> rest;
  int jumped = 0, drifting = 0;
  for (const auto& [t_us, g] : seen.gps) {
    const double t_s = static_cast<double>(t_us) * 1e-6;
    if (in(t_us, 0.2, 0.5)) rest = g;
    if (!rest) continue;
    const double north_m = (g.lat - rest->lat) * m_per_degE7_lat, east_m = (g.lon - rest->lon) * m_per_degE7_lon;
    if (in(t_us, 0.5, 0.8)) {
      EXPECT_NEAR(north_m, 100, 0.5) << t_s;
      EXPECT_NEAR(east_m, -50, 0.5) << t_s;
      EXPECT_EQ(g.vn, 0);
      ++jumped;
    } else if (in(t_us, 0.8, 1.0)) {
      EXPECT_NEAR(north_m, 0, 0.02) << "back after the jump, at " << t_s;
    } else if (t_us + 1 > 1'000'000) {
      EXPECT_NEAR(north_m, 2 * (t_s - 1.0), 0.05) << t_s;
      EXPECT_NEAR(east_m, -1 * (t_s - 1.0), 0.05) << t_s;
      EXPECT_EQ(g.vn, 200);  // cm/s
      EXPECT_EQ(g.ve, -100);
      ++drifting;
    }
  }
  ASSERT_TRUE(rest);
  EXPECT_NEAR(rest->lat * 1e-7, home.lat_deg, 1e-6);
  EXPECT_GE(jumped, 8);  // 30 Hz
  EXPECT_GE(drifting, 15);
}

TEST(SensorFaultsAtTheBoard, GpsNoiseScalesTheFixesErrorAgainstTruth) {
  const auto truth = at_rest({}, 1.0, false), plain = at_rest({}, 1.0, true), loud = at_rest({"gps-noise:3"}, 1.0, true);
  int compared = 0;
  double plain_error = 0;
  for (const auto& [t_us, t] : truth.gps) {
    if (!plain.gps.count(t_us) || !loud.gps.count(t_us) || t_us < 100'000) continue;
    const auto &p = plain.gps.at(t_us), &l = loud.gps.at(t_us);
    // degE7 and cm/s: the scaled error within the rounding of three
    EXPECT_NEAR(l.lat - t.lat, 3.0 * (p.lat - t.lat), 3) << t_us;
    EXPECT_NEAR(l.lon - t.lon, 3.0 * (p.lon - t.lon), 3) << t_us;
    EXPECT_NEAR(l.vn - t.vn, 3.0 * (p.vn - t.vn), 3) << t_us;
    EXPECT_NEAR(l.vd - t.vd, 3.0 * (p.vd - t.vd), 3) << t_us;
    plain_error = std::max(plain_error, std::abs(static_cast<double>(p.lat - t.lat)));
    ++compared;
  }
  EXPECT_GT(compared, 20);
  EXPECT_GT(plain_error, 10) << "the plain fix has an error to scale (degE7)";
}

}  // namespace
}  // namespace hitl::hil
