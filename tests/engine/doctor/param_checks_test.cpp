// The doctor's parameter checks (engine/doctor/param_checks) on fixed inputs: one check per category
// fails alone, and the check it shares with `hitl params check`.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/doctor/check_catalog.h"
#include "engine/doctor/param_checks.h"
#include "engine/vehicle/params_check.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

std::vector<vehicle::Param> defaults_with(const std::string& name, vehicle::ParamValue value) {
  auto p = vehicle::hitl_default_params();
  for (auto& x : p)
    if (x.name == name) x.value = value;
  return p;
}

std::vector<std::string> failing(const std::vector<CheckResult>& results) {
  std::vector<std::string> out;
  for (const auto& r : results)
    if (r.result == Verdict::Fail) out.push_back(r.check);
  return out;
}

TEST(DoctorParams, OneCheckPerCategoryFailsAlone) {
  const auto all = param_checks(vehicle::hitl_default_params());
  ASSERT_EQ(all.size(), 5u);
  EXPECT_TRUE(failing(all).empty());
  auto sys = param_checks(defaults_with("SYS_HITL", vehicle::ParamValue::int32(0)));
  EXPECT_EQ(failing(sys), std::vector<std::string>{check::kParamsSystem});
  EXPECT_TRUE(has(sys[0].saw, "SYS_HITL 0 (spec 1)")) << sys[0].saw;
  EXPECT_TRUE(has(sys[0].fix, "hitl params set SYS_HITL 1")) << sys[0].fix;
  auto cal = param_checks(defaults_with("CAL_ACC0_ID", vehicle::ParamValue::int32(1311244)));
  EXPECT_EQ(failing(cal), std::vector<std::string>{check::kParamsCalibration});
  EXPECT_TRUE(has(cal[1].saw, "dsp_hitl's IMU is 1310988")) << cal[1].saw;
  auto ekf = param_checks(defaults_with("EKF2_GPS_CTRL", vehicle::ParamValue::int32(1)));
  EXPECT_EQ(failing(ekf), std::vector<std::string>{check::kParamsEkf2});
  auto arm = param_checks(defaults_with("CBRK_SUPPLY_CHK", vehicle::ParamValue::int32(0)));
  EXPECT_EQ(failing(arm), std::vector<std::string>{check::kParamsArming});
  auto ca = param_checks(defaults_with("CA_ROTOR0_KM", vehicle::ParamValue::real32(-0.05f)));
  EXPECT_EQ(failing(ca), std::vector<std::string>{check::kParamsAllocation});
  auto gone = param_checks(Error{"no PARAM_VALUE in answer to PARAM_REQUEST_LIST"});
  EXPECT_EQ(failing(gone), std::vector<std::string>{check::kParamsSystem});
  EXPECT_EQ(gone[4].result, Verdict::Skip);
}

TEST(DoctorParams, TheSharedCheckOfHitlParamsCheck) {
  auto board = vehicle::hitl_default_params();
  board.erase(board.begin());  // SYS_AUTOSTART missing
  const auto rows = vehicle::check_params(board, vehicle::hitl_default_params());
  ASSERT_EQ(rows.size(), vehicle::hitl_default_params().size());
  EXPECT_FALSE(rows[0].ok);
  EXPECT_FALSE(rows[0].board.has_value());
  EXPECT_TRUE(has(rows[0].fix, "lacks SYS_AUTOSTART"));
  EXPECT_TRUE(rows[1].ok);
  EXPECT_EQ(vehicle::param_group("CAL_MAG0_ID"), vehicle::ParamGroup::Calibration);
  EXPECT_EQ(vehicle::param_group("COM_ARM_EKF_POS"), vehicle::ParamGroup::Arming);
  EXPECT_EQ(vehicle::param_group("CA_ROTOR_COUNT"), vehicle::ParamGroup::ControlAllocation);
  EXPECT_EQ(vehicle::param_group("IMU_GYRO_RATEMAX"), vehicle::ParamGroup::System);
}

}  // namespace
}  // namespace hitl::doctor
