// Vehicle and world config files: defaults, merge over defaults, errors naming the key.
#include "engine/model/config_json.h"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "engine/model/x500_defaults.h"

namespace hitl::model {
namespace {

TEST(Config, DefaultsRoundTripThroughJson) {
  const std::string vehicle_text = to_json_text(x500_vehicle_config());
  auto vehicle = parse_vehicle_config(vehicle_text, "x500");
  ASSERT_TRUE(vehicle.ok()) << vehicle.error().message;
  EXPECT_EQ(to_json_text(*vehicle), vehicle_text);
  const std::string world_text = to_json_text(default_world_config());
  auto world = parse_world_config(world_text, "world");
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(to_json_text(*world), world_text);
  EXPECT_TRUE(validate(x500_vehicle_config()).ok());
  EXPECT_TRUE(validate(default_world_config()).ok());
  EXPECT_TRUE(validate(with_noise_disabled(x500_vehicle_config())).ok());
}

TEST(Config, EmptyObjectIsTheDefault) {
  auto vehicle = parse_vehicle_config("{}");
  ASSERT_TRUE(vehicle.ok());
  EXPECT_EQ(to_json_text(*vehicle), to_json_text(x500_vehicle_config()));
  auto world = parse_world_config("{ /* comments are allowed */ }");
  ASSERT_TRUE(world.ok());
  EXPECT_EQ(to_json_text(*world), to_json_text(default_world_config()));
}

TEST(Config, PartialFileMergesOverDefaults) {
  auto vehicle = parse_vehicle_config(R"({
    "base": {"mass_kg": 2.5},
    "rotors": [{}, {}, {"time_constant_up_s": 0.02, "turning": "ccw"}, {}],
    "sensors": {"gps": {"delay_s": 0.1}}
  })");
  ASSERT_TRUE(vehicle.ok()) << vehicle.error().message;
  const VehicleConfig d = x500_vehicle_config();
  EXPECT_EQ(vehicle->base.mass_kg, 2.5);
  EXPECT_EQ(vehicle->base.inertia_kgm2, d.base.inertia_kgm2);
  EXPECT_EQ(vehicle->rotors[2].time_constant_up_s, 0.02);
  EXPECT_EQ(vehicle->rotors[2].turning, Turning::Ccw);
  EXPECT_EQ(vehicle->rotors[2].position_FLU_m, d.rotors[2].position_FLU_m);
  EXPECT_EQ(vehicle->rotors[1].time_constant_up_s, d.rotors[1].time_constant_up_s);
  EXPECT_EQ(vehicle->sensors.gps.delay_s, 0.1);
  EXPECT_EQ(vehicle->sensors.gps.rate_hz, 30.0);

  auto world = parse_world_config(R"({"home": {"lat_deg": -33.9}, "wind": {"velocity_ENU_m_s": [3, 0, 0]}})");
  ASSERT_TRUE(world.ok()) << world.error().message;
  EXPECT_EQ(world->home.lat_deg, -33.9);
  EXPECT_EQ(world->home.lon_deg, default_world_config().home.lon_deg);
  EXPECT_EQ(world->wind.velocity_ENU_m_s, Eigen::Vector3d(3, 0, 0));
}

TEST(Config, OutOfRangeNamesFileKeyAndValue) {
  auto v = parse_vehicle_config(R"({"rotors": [{}, {}, {"time_constant_up_s": -1}, {}]})", "vehicle.json");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.error().message, "vehicle.json: rotors[2].time_constant_up_s: must be > 0 (got -1)");

  auto w = parse_world_config(R"({"home": {"lat_deg": 91}})", "world.json");
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.error().message, "world.json: home.lat_deg: must be in [-90, 90] (got 91)");
}

TEST(Config, ImuRangeAndGroundContactKeys) {
  auto v = parse_vehicle_config(R"({"sensors": {"imu": {"accel_range_m_s2": 78.45, "gyro_range_rad_s": 17.45}},
                                   "landing_gear": {"damping_depth_m": 0.01, "frame_stiffness_N_m": 5000,
                                                    "frame_points_FLU_m": [[0,0,0.1],[0,0,0.1],[0,0,0.1],[0,0,0.1]]}})",
                                "vehicle.json");
  ASSERT_TRUE(v.ok()) << v.error().message;
  EXPECT_EQ(v.value().sensors.imu.accel_range_m_s2, 78.45);
  EXPECT_EQ(v.value().sensors.imu.gyro_range_rad_s, 17.45);
  EXPECT_EQ(v.value().landing_gear.damping_depth_m, 0.01);
  EXPECT_EQ(v.value().landing_gear.frame_stiffness_N_m, 5000);
  auto bad = parse_vehicle_config(R"({"sensors": {"imu": {"accel_range_m_s2": 0}}})", "vehicle.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "vehicle.json: sensors.imu.accel_range_m_s2: must be > 0 (got 0)");
}

TEST(Config, UnknownKeysAreErrors) {
  auto v = parse_vehicle_config(R"({"base": {"mas_kg": 2}, "colour": "red"})", "vehicle.json");
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.error().message.find("vehicle.json: base.mas_kg: unknown key"), std::string::npos) << v.error().message;
  EXPECT_NE(v.error().message.find("vehicle.json: colour: unknown key"), std::string::npos) << v.error().message;
  auto r = parse_vehicle_config(R"({"rotors": [{}, {}, {}, {"kf": 1}]})", "v.json");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message, "v.json: rotors[3].kf: unknown key");
}

TEST(Config, WrongShapesAreErrors) {
  auto type = parse_vehicle_config(R"({"base": {"mass_kg": "heavy"}})", "v.json");
  ASSERT_FALSE(type.ok());
  EXPECT_EQ(type.error().message, "v.json: base.mass_kg: must be a number (got \"heavy\")");
  auto count = parse_vehicle_config(R"({"rotors": [{}, {}, {}]})", "v.json");
  ASSERT_FALSE(count.ok());
  EXPECT_NE(count.error().message.find("v.json: rotors: must be an array of 4"), std::string::npos) << count.error().message;
  auto vec = parse_vehicle_config(R"({"base": {"inertia_kgm2": [1, 2]}})", "v.json");
  ASSERT_FALSE(vec.ok());
  EXPECT_NE(vec.error().message.find("v.json: base.inertia_kgm2: must be an array of 3 numbers"), std::string::npos);
  auto elem = parse_vehicle_config(R"({"base": {"inertia_kgm2": [1, -2, 3]}})", "v.json");
  ASSERT_FALSE(elem.ok());
  EXPECT_EQ(elem.error().message, "v.json: base.inertia_kgm2[1]: must be > 0 (got -2)");
  auto turning = parse_vehicle_config(R"({"rotors": [{"turning": "left"}, {}, {}, {}]})", "v.json");
  ASSERT_FALSE(turning.ok());
  EXPECT_EQ(turning.error().message, "v.json: rotors[0].turning: must be \"ccw\" or \"cw\" (got \"left\")");
  auto sats = parse_vehicle_config(R"({"sensors": {"gps": {"satellites": 9.5}}})", "v.json");
  ASSERT_FALSE(sats.ok());
  EXPECT_EQ(sats.error().message, "v.json: sensors.gps.satellites: must be an integer (got 9.5)");
  auto json = parse_world_config("{\"gravity_m_s2\": ", "w.json");
  ASSERT_FALSE(json.ok());
  EXPECT_EQ(json.error().message.rfind("w.json: not valid JSON", 0), 0u) << json.error().message;
  auto array = parse_world_config("[]", "w.json");
  ASSERT_FALSE(array.ok());
  EXPECT_EQ(array.error().message, "w.json: must be a JSON object (got array)");
}

TEST(Config, AllErrorsAreReportedOneALine) {
  auto v = parse_vehicle_config(R"({"base": {"mass_kg": 0, "linear_drag_N_s_m": [0, 0, -1]}, "sensors": {"imu": {"rate_hz": 0}}})", "v.json");
  ASSERT_FALSE(v.ok());
  EXPECT_EQ(v.error().message,
            "v.json: base.mass_kg: must be > 0 (got 0)\n"
            "v.json: base.linear_drag_N_s_m[2]: must be >= 0 (got -1)\n"
            "v.json: sensors.imu.rate_hz: must be in [0.1, 10000] (got 0)");
}

TEST(Config, LoadsFilesAndNamesMissingOnes) {
  const std::string path = ::testing::TempDir() + "hitl_world_test.json";
  {
    std::ofstream out(path);
    out << R"({"magnetic_field": {"declination_deg": 10.5}})";
  }
  auto w = load_world_config(path);
  ASSERT_TRUE(w.ok()) << w.error().message;
  EXPECT_EQ(w->magnetic_field.declination_deg, 10.5);
  {
    std::ofstream out(path);
    out << R"({"physics": {"step_s": 0}})";
  }
  auto bad = load_world_config(path);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, path + ": physics.step_s: must be in [0.0001, 0.1] (got 0)");
  std::remove(path.c_str());
  auto missing = load_vehicle_config("/nonexistent/vehicle.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message, "cannot read vehicle file '/nonexistent/vehicle.json': No such file or directory");
}

TEST(Config, ValidateCatchesConfigsBuiltInCode) {
  VehicleConfig v = x500_vehicle_config();
  v.rotors[1].motor_constant_N_s2 = std::nan("");
  const Status s = validate(v);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().message, "vehicle config: rotors[1].motor_constant_N_s2: must be a number (got null)");
}

TEST(Config, DefaultWorldMatchesPx4Home) {
  const WorldConfig w = default_world_config();
  EXPECT_EQ(w.home.lat_deg, 47.397742);
  EXPECT_EQ(w.home.lon_deg, 8.545594);
  EXPECT_EQ(w.home.alt_m, 488.0);
  EXPECT_EQ(w.gravity_m_s2, 9.80665);
  EXPECT_EQ(w.physics.step_s, 0.004);
  // About +3 deg declination, +63 deg inclination, 0.48 G (x500.md).
  EXPECT_NEAR(w.magnetic_field.declination_deg, 3.0, 0.5);
  EXPECT_NEAR(w.magnetic_field.inclination_deg, 63.0, 0.5);
  EXPECT_NEAR(w.magnetic_field.strength_gauss, 0.48, 0.01);
}

}  // namespace
}  // namespace hitl::model
