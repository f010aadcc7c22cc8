#include <gtest/gtest.h>

#include <cmath>

#include "engine/vehicle/trajectory.h"

namespace hitl::vehicle {
namespace {

TEST(Trajectory, InterpolatesLinearlyAndYawTheShortWayRound) {
  auto t = Trajectory::parse(R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 3.0},
                                              {"t": 10, "x": 10, "y": -5, "z": 4, "yaw": -3.0}]})",
                             "t.json");
  ASSERT_TRUE(t.ok()) << t.error().message;
  const auto mid = t->at(5);
  EXPECT_DOUBLE_EQ(mid.p_ENU_m[0], 5);
  EXPECT_DOUBLE_EQ(mid.p_ENU_m[1], -2.5);
  EXPECT_DOUBLE_EQ(mid.p_ENU_m[2], 3);
  EXPECT_DOUBLE_EQ(mid.v_ENU_m_s[0], 1.0);
  // 3.0 -> -3.0 rad goes through pi (0.28 rad), not through 0 (6 rad).
  EXPECT_NEAR(std::fabs(mid.yaw_ENU_rad), M_PI, 1e-9);
  EXPECT_DOUBLE_EQ(t->at(-1).p_ENU_m[0], 0);
  EXPECT_DOUBLE_EQ(t->at(99).p_ENU_m[0], 10);
  EXPECT_DOUBLE_EQ(t->duration_s(), 10);
}

TEST(Trajectory, BadFilesNameTheWaypointAndField) {
  auto expect_error = [](const char* text, const char* what) {
    auto t = Trajectory::parse(text, "f.json");
    ASSERT_FALSE(t.ok()) << text;
    EXPECT_NE(t.error().message.find(what), std::string::npos) << t.error().message;
  };
  expect_error("not json", "not valid JSON");
  expect_error(R"({"points": []})", "\"waypoints\" array");
  expect_error(R"({"waypoints": []})", "empty");
  expect_error(R"({"waypoints": [{"t": 0, "x": 0, "y": 0}]})", "waypoints[0].z: missing");
  expect_error(R"({"waypoints": [{"t": 0, "x": "a", "y": 0, "z": 1}]})", "waypoints[0].x: must be a number");
  expect_error(R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 1}, {"t": 0, "x": 1, "y": 0, "z": 1}]})",
               "waypoints[1].t: times must increase");
  expect_error(R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 1, "speed": 3}]})", "waypoints[0].speed: unknown field");
  expect_error(R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": -1}]})", "waypoints[0].z: must be >= 0");
  EXPECT_FALSE(Trajectory::load("/nonexistent.json").ok());
}

TEST(Trajectory, ExampleFilesParse) {
  for (const char* f : {"square.json", "hover.json"}) {
    auto t = Trajectory::load(std::string(HITL_SOURCE_DIR) + "/docs/examples/" + f);
    EXPECT_TRUE(t.ok()) << f << ": " << (t.ok() ? "" : t.error().message);
  }
}

}  // namespace
}  // namespace hitl::vehicle
