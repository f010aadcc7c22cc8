#include <gtest/gtest.h>

#include <map>

#include "engine/vehicle/params_file.h"

namespace hitl::vehicle {
namespace {

TEST(ParamsFile, CompiledDefaultsHoldTheSpecsHitlSet) {
  std::map<std::string, ParamValue> p;
  for (const auto& param : hitl_default_params()) p[param.name] = param.value;
  ASSERT_GE(p.size(), 40u);  // the data file parsed (a parse error would leave it empty)
  // The spec's "HITL Default Parameters" tables.
  EXPECT_EQ(p.at("SYS_AUTOSTART"), ParamValue::int32(1001));
  EXPECT_EQ(p.at("SYS_HITL"), ParamValue::int32(1));
  EXPECT_EQ(p.at("IMU_GYRO_RATEMAX"), ParamValue::int32(800));
  EXPECT_EQ(p.at("CAL_ACC0_ID"), ParamValue::int32(1310988));
  EXPECT_EQ(p.at("CAL_GYRO0_ID"), ParamValue::int32(1310988));
  EXPECT_EQ(p.at("CAL_MAG0_ID"), ParamValue::int32(197388));
  EXPECT_EQ(p.at("EKF2_GPS_CHECK"), ParamValue::int32(0));
  EXPECT_EQ(p.at("EKF2_HGT_REF"), ParamValue::int32(1));
  EXPECT_EQ(p.at("EKF2_MAG_TYPE"), ParamValue::int32(1));
  EXPECT_EQ(p.at("EKF2_MAG_CHECK"), ParamValue::int32(0));
  EXPECT_EQ(p.at("EKF2_BARO_CTRL"), ParamValue::int32(1));
  EXPECT_EQ(p.at("EKF2_GPS_CTRL"), ParamValue::int32(7));
  EXPECT_EQ(p.at("CBRK_SUPPLY_CHK"), ParamValue::int32(894281));
  EXPECT_EQ(p.at("CBRK_IO_SAFETY"), ParamValue::int32(22027));
  EXPECT_EQ(p.at("COM_ARM_MAG_STR"), ParamValue::int32(0));
  EXPECT_EQ(p.at("COM_ARM_EKF_POS"), ParamValue::real32(1.0f));
  EXPECT_EQ(p.at("COM_ARM_EKF_VEL"), ParamValue::real32(1.0f));
  EXPECT_EQ(p.at("CA_ROTOR0_PX"), ParamValue::real32(0.174f));
  EXPECT_EQ(p.at("CA_ROTOR1_PY"), ParamValue::real32(-0.174f));
  EXPECT_EQ(p.at("CA_ROTOR2_KM"), ParamValue::real32(-0.05f));
  EXPECT_EQ(p.at("CA_ROTOR3_PY"), ParamValue::real32(0.174f));
}

TEST(ParamsFile, RoundTripAndErrorsNameTheLine) {
  std::vector<Param> params{{"SYS_HITL", ParamValue::int32(1)}, {"MPC_XY_P", ParamValue::real32(0.95f)}};
  const auto text = format_params(params);
  auto back = parse_params(text, "x.params");
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_EQ(back->size(), 2u);
  EXPECT_EQ((*back)[0].value, params[0].value);
  EXPECT_EQ((*back)[1].value, params[1].value);
  auto bad = parse_params("1 1 SYS_HITL one 6\n", "x.params");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("x.params:1: SYS_HITL"), std::string::npos) << bad.error().message;
  EXPECT_FALSE(parse_params("1 1 A 1 7\n", "x").ok());
  EXPECT_FALSE(parse_params("1 1 A\n", "x").ok());
  EXPECT_FALSE(parse_params("1 1 A 9999999999 6\n", "x").ok());
  EXPECT_FALSE(parse_params("1 1 ABCDEFGHIJKLMNOPQ 1 6\n", "x").ok());
  EXPECT_FALSE(load_params_file("/nonexistent.params").ok());
}

TEST(ParamsFile, OneValueCheckForLoadAndSet) {
  EXPECT_EQ(parse_param_value("2147483647", ParamType::Int32).value(), ParamValue::int32(2147483647));
  EXPECT_EQ(parse_param_value("-2147483648", ParamType::Int32).value(), ParamValue::int32(INT32_MIN));
  for (const char* bad : {"2147483648", "99999999999", "4294967297", "1.5", "", "1 ", "nan"})
    EXPECT_FALSE(parse_param_value(bad, ParamType::Int32).ok()) << bad;
  EXPECT_EQ(parse_param_value("0.5", ParamType::Real32).value(), ParamValue::real32(0.5f));
  for (const char* bad : {"nan", "inf", "1e39", "-1e39", "x"}) EXPECT_FALSE(parse_param_value(bad, ParamType::Real32).ok()) << bad;
  // The file names the line and the parameter before the same words.
  auto wrapped = parse_params("1 1 SYS_HITL 4294967297 6\n", "x.params");
  ASSERT_FALSE(wrapped.ok());
  EXPECT_EQ(wrapped.error().message,
            "x.params:1: SYS_HITL: value '4294967297' is not a valid INT32 (an integer from -2147483648 to 2147483647)");
}

TEST(ParamsFile, Int32TravelsBytewiseInTheFloatField) {
  const auto v = ParamValue::int32(1310988);
  const float wire = encode_param_float(v);
  EXPECT_NE(wire, 1310988.0f);  // not converted, reinterpreted
  EXPECT_EQ(decode_param_float(wire, ParamType::Int32), v);
  EXPECT_EQ(decode_param_float(0.5f, ParamType::Real32), ParamValue::real32(0.5f));
}

}  // namespace
}  // namespace hitl::vehicle
