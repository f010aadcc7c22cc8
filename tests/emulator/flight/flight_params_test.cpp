// The parameter table: every row matches its member's default, names are unique and fit
// PARAM_VALUE's 16 characters, set/get by name with range checks.
#include "emulator/flight/flight_params.h"

#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "emulator/flight/px4_modes.h"

namespace hitl::flight {
namespace {

TEST(FlightParams, TableMatchesTheStructDefaults) {
  const FlightParams defaults;
  std::set<std::string> names;
  for (const ParamInfo& p : param_table()) {
    SCOPED_TRACE(p.name);
    EXPECT_LE(std::string(p.name).size(), 16u);
    EXPECT_TRUE(names.insert(p.name).second) << "duplicate";
    const double value = *get_param(defaults, p.name);
    EXPECT_EQ(static_cast<float>(value), static_cast<float>(p.default_value));
    EXPECT_LE(p.min_value, value);
    EXPECT_GE(p.max_value, value);
    EXPECT_EQ(p.type == ParamType::Float, p.f != nullptr);
    EXPECT_EQ(p.type == ParamType::Int32, p.i != nullptr);
  }
  EXPECT_EQ(param_table().size(), sizeof(FlightParams) / 4);  // every member is listed (all 4 bytes)
}

TEST(FlightParams, SetAndGetByName) {
  FlightParams p;
  EXPECT_EQ(set_param(p, "MPC_XY_P", 1.2), ParamResult::Success);
  EXPECT_FLOAT_EQ(p.MPC_XY_P, 1.2f);
  EXPECT_EQ(set_param(p, "EKF2_REQ_NSATS", 7.4), ParamResult::Success);
  EXPECT_EQ(p.EKF2_REQ_NSATS, 7);
  EXPECT_EQ(set_param(p, "MPC_XY_P", 99.0), ParamResult::OutOfRange);
  EXPECT_EQ(set_param(p, "NO_SUCH_PARAM", 1.0), ParamResult::UnknownName);
  EXPECT_EQ(set_param(p, "MPC_Z_P", std::nan("")), ParamResult::NotANumber);
  EXPECT_FALSE(get_param(p, "NO_SUCH_PARAM").has_value());
  EXPECT_DOUBLE_EQ(*get_param(p, "CA_ROTOR2_KM"), static_cast<double>(-0.05f));
}

TEST(Px4Modes, CustomModeWords) {
  EXPECT_EQ(px4_custom_mode(FlightMode::Position), 0x00030000u);
  EXPECT_EQ(px4_custom_mode(FlightMode::Hold), 0x03040000u);
  EXPECT_EQ(px4_custom_mode(FlightMode::Takeoff), 0x02040000u);
  EXPECT_EQ(px4_custom_mode(FlightMode::Land), 0x06040000u);
  for (FlightMode m : {FlightMode::Position, FlightMode::Hold, FlightMode::Takeoff, FlightMode::Land}) {
    EXPECT_EQ(flight_mode_from_px4(px4_custom_mode(m)), m);
  }
  EXPECT_FALSE(flight_mode_from_px4(0x00010000u).has_value());  // MANUAL
  EXPECT_EQ(mav_base_mode(FlightMode::Hold, true) & mav_mode_flag::kSafetyArmed, mav_mode_flag::kSafetyArmed);
  EXPECT_EQ(mav_base_mode(FlightMode::Hold, false) & mav_mode_flag::kSafetyArmed, 0);
}

}  // namespace
}  // namespace hitl::flight
