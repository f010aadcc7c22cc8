// The rangefinder unit (engine/sensors/rangefinder): its geometry over flat ground, its range
// limits, its noise, its faults, its DISTANCE_SENSOR, its schedule in the suite and its keys in the
// vehicle file.
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/mavlink/enums.h"
#include "engine/model/x500_defaults.h"
#include "engine/sensors/sensor_suite.h"
#include "engine/sensors/vehicle_file.h"
#include "tests/support/statistics.h"

namespace hitl::sensors {
namespace {

using Config = Rangefinder::Config;

model::VehicleState at(double z_m, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  model::VehicleState s;
  s.p_ENU_m = {3.0, -2.0, z_m};
  s.q_FLU_to_ENU = q;
  return s;
}

Config noiseless() { return Rangefinder::without_noise(Config{}); }

TEST(Rangefinder, LevelReadsTheMountsHeightAboveTheGround) {
  Rangefinder r(noiseless(), model::default_world_config(), 1);
  const auto s = r.sample(at(2.0), 0.01);
  EXPECT_TRUE(s.valid);
  EXPECT_NEAR(s.distance_m, 1.95, 1e-12);  // the mount is 5 cm below the base origin
  EXPECT_DOUBLE_EQ(s.true_distance_m, s.distance_m);
}

TEST(Rangefinder, TiltedReadsTheSlantRangeAlongTheBeam) {
  Rangefinder r(noiseless(), model::default_world_config(), 1);
  const double roll_rad = 30.0 * std::numbers::pi / 180.0;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()));
  const double mount_z_m = 2.0 - 0.05 * std::cos(roll_rad);
  EXPECT_NEAR(r.sample(at(2.0, q), 0.01).distance_m, mount_z_m / std::cos(roll_rad), 1e-12);
}

TEST(Rangefinder, NoValidReturnOutsideItsRangeOrPointingUp) {
  Rangefinder r(noiseless(), model::default_world_config(), 1);
  for (const auto& state : {at(12.2), at(0.1), at(2.0, Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitX())))}) {
    const auto s = r.sample(state, 0.01);
    EXPECT_FALSE(s.valid);
    EXPECT_DOUBLE_EQ(s.distance_m, 12.01);
    const auto m = r.message(s, 10000);
    EXPECT_EQ(m.current_distance, 1201);
    EXPECT_EQ(m.signal_quality, 1);  // MAVLink: invalid
  }
  EXPECT_TRUE(r.sample(at(11.9), 0.01).valid);
}

TEST(Rangefinder, DistanceSensorAsPx4ReadsIt) {
  Rangefinder r(Config{}, model::default_world_config(), 1);
  auto s = r.sample(at(2.0), 0.25);
  s.distance_m = 1.954;  // as if drawn so
  const auto m = r.message(s, 250000);
  EXPECT_EQ(m.time_boot_ms, 250u);
  EXPECT_EQ(m.min_distance, 10);    // cm: the TFmini Plus's 0.1 m
  EXPECT_EQ(m.max_distance, 1200);  // cm: 12 m
  EXPECT_EQ(m.current_distance, 195);
  EXPECT_EQ(m.type, static_cast<uint8_t>(mavlink::MavDistanceSensor::Laser));
  EXPECT_EQ(m.orientation, 25);  // MAV_SENSOR_ROTATION_PITCH_270: downward-facing in PX4
  EXPECT_EQ(m.covariance, 6);    // (2.5 cm)^2, rounded
  EXPECT_NEAR(m.horizontal_fov, 3.6 * std::numbers::pi / 180.0, 1e-6);
  EXPECT_NEAR(m.vertical_fov, 3.6 * std::numbers::pi / 180.0, 1e-6);
  EXPECT_EQ(m.signal_quality, 100);
  s.distance_m = 10.0;  // sigma 0.5 % of 10 m = 5 cm
  EXPECT_EQ(r.message(s, 0).covariance, 25);
}

TEST(Rangefinder, NoiseHasItsSigmaNearAndFar) {
  for (const double z_m : {2.05, 10.05}) {
    Rangefinder r(Config{}, model::default_world_config(), 7);
    std::vector<double> x;
    for (int k = 0; k < 4000; ++k) x.push_back(r.sample(at(z_m), 0.01 * (k + 1)).distance_m);
    const double expected = std::max(0.025, 0.005 * (z_m - 0.05));
    EXPECT_NEAR(test::sample_sigma(x), expected, 0.06 * expected) << z_m;
  }
}

TEST(Rangefinder, StuckRepeatsTheLastReadingNoReturnReportsNone) {
  Rangefinder r(Config{}, model::default_world_config(), 1);
  Rangefinder::Faults none, stuck, no_return;
  stuck.stuck = true;
  no_return.no_return = true;
  auto before = r.sample(at(1.0), 0.01);
  r.apply(none, before);
  for (int k = 2; k < 6; ++k) {
    auto s = r.sample(at(1.0 + k), 0.01 * k);
    r.apply(stuck, s);
    EXPECT_EQ(s.distance_m, before.distance_m);
  }
  auto after = r.sample(at(4.0), 0.07);
  r.apply(none, after);
  EXPECT_NEAR(after.distance_m, 3.95, 0.2);
  r.apply(no_return, after);
  EXPECT_FALSE(after.valid);
  EXPECT_DOUBLE_EQ(after.distance_m, 12.01);
}

TEST(Rangefinder, OffByDefaultOnItsOwnScheduleWhenOn) {
  const auto vehicle = model::x500_vehicle_config();
  const auto world = model::default_world_config();
  SensorSuite off(vehicle, world, 1);
  UnitConfigs units;
  std::get<Config>(units).enabled = true;
  SensorSuite on(vehicle, world, 1, units);
  int off_samples = 0, on_samples = 0;
  double first_s = -1;
  for (int k = 1; k <= 250; ++k) {  // 1 s of 4 ms steps
    auto s = at(1.5);
    s.time_s = 0.004 * k;
    if (std::get<0>(off.sample_due(s).units)) ++off_samples;
    const auto frame = on.sample_due(s);  // held: a reference into a temporary frame would dangle
    if (const auto& r = std::get<0>(frame.units)) {
      ++on_samples;
      if (first_s < 0) first_s = r->time_s;
    }
  }
  EXPECT_EQ(off_samples, 0);
  EXPECT_EQ(on_samples, 101);  // 100 Hz: at 4 ms, then 10, 20, ... 1000 ms
  EXPECT_DOUBLE_EQ(first_s, 0.004);  // not before the first IMU period, as the other sensors
}

TEST(VehicleFile, ReadsTheUnitsSectionsOverTheirDefaults) {
  auto file = parse_vehicle_file(R"({"base": {"mass_kg": 2.5}, "sensors": {"rangefinder": {"enabled": true, "rate_hz": 50},
                                     "baro": {"noise_pa": 3}}})", "v.json");
  ASSERT_TRUE(file) << file.error().message;
  const auto& r = std::get<Config>(file->units);
  EXPECT_TRUE(r.enabled);
  EXPECT_EQ(r.rate_hz, 50.0);
  EXPECT_EQ(r.max_distance_m, 12.0);
  EXPECT_EQ(file->vehicle.base.mass_kg, 2.5);
  EXPECT_EQ(file->vehicle.sensors.baro.noise_pa, 3.0);
  auto plain = parse_vehicle_file("{}", "v.json");
  ASSERT_TRUE(plain);
  EXPECT_FALSE(std::get<Config>(plain->units).enabled);  // off by default
  // The complete file reads back as it was.
  auto again = parse_vehicle_file(to_json_text(*file), "again.json");
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_TRUE(std::get<Config>(again->units).enabled);
  EXPECT_EQ(std::get<Config>(again->units).rate_hz, 50.0);
}

TEST(VehicleFile, ErrorsNameTheUnitsKeysWithTheVehiclesErrors) {
  auto bad = parse_vehicle_file(R"({"base": {"mass_kg": -1}, "sensors": {"rangefinder": {"rate_hz": 0, "range_m": 3, "enabled": 1}}})", "v.json");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().kind, ErrorKind::Input);
  const std::string& m = bad.error().message;
  EXPECT_NE(m.find("v.json: base.mass_kg: must be > 0"), std::string::npos) << m;
  EXPECT_NE(m.find("v.json: sensors.rangefinder.rate_hz: must be in [0.1, 10000] (got 0)"), std::string::npos) << m;
  EXPECT_NE(m.find("v.json: sensors.rangefinder.range_m: unknown key"), std::string::npos) << m;
  EXPECT_NE(m.find("v.json: sensors.rangefinder.enabled: must be true or false (got 1)"), std::string::npos) << m;
  auto crossed = parse_vehicle_file(R"({"sensors": {"rangefinder": {"min_distance_m": 5, "max_distance_m": 4}}})", "v.json");
  ASSERT_FALSE(crossed);
  EXPECT_NE(crossed.error().message.find("sensors.rangefinder: min_distance_m must be less than max_distance_m"), std::string::npos)
      << crossed.error().message;
  auto not_object = parse_vehicle_file(R"({"sensors": {"rangefinder": true}})", "v.json");
  ASSERT_FALSE(not_object);
  EXPECT_NE(not_object.error().message.find("sensors.rangefinder: must be an object"), std::string::npos);
  EXPECT_FALSE(parse_vehicle_file("{", "v.json"));
}

TEST(VehicleFile, ListsEveryUnitKey) {
  const auto keys = unit_keys();
  for (const char* k : {"sensors.rangefinder.enabled", "sensors.rangefinder.rate_hz", "sensors.rangefinder.min_distance_m",
                        "sensors.rangefinder.max_distance_m", "sensors.rangefinder.noise_m", "sensors.rangefinder.noise_fraction",
                        "sensors.rangefinder.fov_deg", "sensors.rangefinder.position_FLU_m"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end()) << k;
}

// docs/engine.md's vehicle table has every unit's key (a new unit's keys must be documented).
TEST(VehicleFile, EveryUnitKeyIsInTheEngineDocs) {
  std::ifstream in(std::string(HITL_SOURCE_DIR) + "/docs/engine.md");
  ASSERT_TRUE(in) << "docs/engine.md";
  std::stringstream text;
  text << in.rdbuf();
  for (const auto& key : unit_keys()) EXPECT_NE(text.str().find("| `" + key + "` |"), std::string::npos) << key;
}

// The SensorUnit concept is what makes a forgotten part a compile error: a unit with every part
// satisfies it, and the same unit without any one part does not (each static_assert below is a
// test that runs when this file compiles).
namespace parts {
struct Sample {};
struct Faults {};
struct Config {
  bool enabled = false;
  double rate_hz = 1.0;
};
template <bool kMessage = true, bool kFaults = true, bool kCheck = true, bool kApply = true>
struct Unit {
  using Sample = parts::Sample;
  using Faults = parts::Faults;
  using Config = parts::Config;
  static constexpr const char* kName = "unit";
  static constexpr const char* kSummary = "a unit";
  template <class V>
  static void fields(V& v, Config& c) { v.boolean("enabled", c.enabled); }
  static std::string check(const Config&) requires kCheck { return ""; }
  static Config without_noise(Config c) { return c; }
  static const std::vector<UnitFault<Faults>>& faults() requires kFaults {
    static const std::vector<UnitFault<Faults>> none;
    return none;
  }
  Unit(const Config&, const model::WorldConfig&, std::uint64_t) {}
  Sample sample(const model::VehicleState&, double) { return {}; }
  void reset() {}
  void apply(const Faults&, Sample&) requires kApply {}
  mavlink::msg::DistanceSensor message(const Sample&, std::uint64_t) const requires kMessage { return {}; }
};
}  // namespace parts
static_assert(SensorUnit<Rangefinder>);
static_assert(SensorUnit<parts::Unit<>>);
static_assert(!SensorUnit<parts::Unit<false, true, true, true>>, "no wire encoding");
static_assert(!SensorUnit<parts::Unit<true, false, true, true>>, "no fault table");
static_assert(!SensorUnit<parts::Unit<true, true, false, true>>, "no config check");
static_assert(!SensorUnit<parts::Unit<true, true, true, false>>, "no fault application");

}  // namespace
}  // namespace hitl::sensors
