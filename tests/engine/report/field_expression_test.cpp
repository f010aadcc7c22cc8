// hitl report --plot's expressions (field_expression.h): the grammar, the fields checked against the
// codec's messages, every refusal with its position, the bounds; evaluated on real payloads.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/report/field_expression.h"

namespace hitl::report {
namespace {
namespace msg = mavlink::msg;

const mavlink::MessageSet& messages() {
  static const auto set = mavlink::MessageSet::compiled();
  return set;
}

/// The payload of `m` as the parser keeps it (zero-extended).
template <class M>
mavlink::Frame frame_of(const M& m) {
  mavlink::FrameEncoder enc(1, 1);
  mavlink::FrameBuffer buf;
  const std::size_t n = enc.encode(m, buf);
  mavlink::FrameParser parser(messages());
  mavlink::Frame out;
  parser.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) { out = f; });
  return out;
}

std::string error_of(std::string_view text, const FieldPlotLimits& limits = {}) {
  auto r = parse_field_plot(text, messages(), limits);
  return r ? "(parsed)" : r.error().message;
}

TEST(FieldExpression, SeriesAreSplitAtCommasAndEvaluatedOnTheirMessage) {
  msg::Attitude a;
  a.roll = 0.5F;
  a.pitch = -0.25F;
  a.yaw = 2.0F;
  const auto f = frame_of(a);
  auto spec = parse_field_plot(" ATTITUDE.roll , ATTITUDE.pitch*2,degrees(ATTITUDE.yaw)", messages());
  ASSERT_TRUE(spec) << spec.error().message;
  ASSERT_EQ(spec->series.size(), 3u);
  EXPECT_EQ(spec->series[0].text, "ATTITUDE.roll");
  EXPECT_EQ(spec->series[0].message, "ATTITUDE");
  EXPECT_EQ(spec->series[0].msgid, msg::Attitude::kId);
  EXPECT_EQ(spec->series[0].units, "rad");  // one field alone: its units
  EXPECT_EQ(spec->series[1].units, "");
  EXPECT_DOUBLE_EQ(spec->series[0].evaluate(f.payload.data()), 0.5);
  EXPECT_DOUBLE_EQ(spec->series[1].evaluate(f.payload.data()), -0.5);
  EXPECT_NEAR(spec->series[2].evaluate(f.payload.data()), 114.591559, 1e-5);
}

TEST(FieldExpression, ArithmeticHasItsUsualPrecedenceSignsAndParentheses) {
  msg::GlobalPositionInt g;
  g.relative_alt = 2500;  // mm
  g.vx = -300;            // cm/s
  g.hdg = 9000;
  const auto f = frame_of(g);
  auto value = [&](std::string_view text) {
    auto spec = parse_field_plot(text, messages());
    EXPECT_TRUE(spec) << text << ": " << (spec ? "" : spec.error().message);
    return spec ? spec->series.at(0).evaluate(f.payload.data()) : NAN;
  };
  EXPECT_DOUBLE_EQ(value("GLOBAL_POSITION_INT.relative_alt/1000"), 2.5);
  EXPECT_DOUBLE_EQ(value("1+GLOBAL_POSITION_INT.relative_alt/1000*2"), 6.0);
  EXPECT_DOUBLE_EQ(value("(1+GLOBAL_POSITION_INT.relative_alt/1000)*2"), 7.0);
  EXPECT_DOUBLE_EQ(value("-GLOBAL_POSITION_INT.vx/100"), 3.0);
  EXPECT_DOUBLE_EQ(value("--GLOBAL_POSITION_INT.vx"), -300.0);
  EXPECT_DOUBLE_EQ(value("10 - 2 - GLOBAL_POSITION_INT.hdg / 1000 / 3"), 5.0);  // left to right
  EXPECT_DOUBLE_EQ(value("abs(GLOBAL_POSITION_INT.vx) + sqrt(16) + 1.5e2*0"), 304.0);
  EXPECT_NEAR(value("radians(GLOBAL_POSITION_INT.hdg/100)"), M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(value("GLOBAL_POSITION_INT.relative_alt/GLOBAL_POSITION_INT.relative_alt"), 1.0);
}

TEST(FieldExpression, ArrayFieldsTakeAnIndexAndExtensionsReadAsSent) {
  msg::HilActuatorControls h;
  h.controls[0] = 0.25F;
  h.controls[15] = 0.75F;
  const auto f = frame_of(h);
  auto spec = parse_field_plot("HIL_ACTUATOR_CONTROLS.controls[0],HIL_ACTUATOR_CONTROLS.controls[ 15 ]", messages());
  ASSERT_TRUE(spec) << spec.error().message;
  EXPECT_DOUBLE_EQ(spec->series[0].evaluate(f.payload.data()), 0.25);
  EXPECT_DOUBLE_EQ(spec->series[1].evaluate(f.payload.data()), 0.75);
  msg::Odometry o;
  o.q = {1, 0, 0, 0};
  o.estimator_type = 6;  // an extension field
  const auto of = frame_of(o);
  auto ext = parse_field_plot("ODOMETRY.estimator_type,ODOMETRY.q[0]", messages());
  ASSERT_TRUE(ext) << ext.error().message;
  EXPECT_DOUBLE_EQ(ext->series[0].evaluate(of.payload.data()), 6.0);
  EXPECT_DOUBLE_EQ(ext->series[1].evaluate(of.payload.data()), 1.0);
}

TEST(FieldExpression, ADivisionByAFieldThatIsZeroIsNotFinite) {
  msg::Attitude a;  // all 0
  auto spec = parse_field_plot("1/ATTITUDE.roll", messages());
  ASSERT_TRUE(spec) << spec.error().message;
  EXPECT_FALSE(std::isfinite(spec->series[0].evaluate(frame_of(a).payload.data())));
}

TEST(FieldExpression, BadInputIsRefusedWithItsPositionAndWhy) {
  EXPECT_EQ(error_of("ATTITUDE.rol"), "'ATTITUDE.rol' at character 10: ATTITUDE has no field 'rol' (its fields: time_boot_ms, "
                                      "roll, pitch, yaw, rollspeed, pitchspeed, yawspeed)");
  EXPECT_EQ(error_of("ATTITUDE.roll,ATTITUDE.pitch+"),
            "'ATTITUDE.roll,ATTITUDE.pitch+' at character 30: the series ends where a number, a field or '(' was expected");
  EXPECT_NE(error_of("ATITUDE.roll").find("'ATITUDE.roll' at character 1: no message 'ATITUDE' in hitl's MAVLink set (HEARTBEAT, "),
            std::string::npos);
  EXPECT_EQ(error_of("ATTITUDE.roll+SCALED_IMU.xacc"),
            "'ATTITUDE.roll+SCALED_IMU.xacc' at character 15: a series takes the fields of one message: this one is of ATTITUDE, "
            "not SCALED_IMU");
  EXPECT_EQ(error_of("HIL_ACTUATOR_CONTROLS.controls"),
            "'HIL_ACTUATOR_CONTROLS.controls' at character 23: HIL_ACTUATOR_CONTROLS.controls is an array of 16: name one element, "
            "controls[0] to controls[15]");
  EXPECT_EQ(error_of("HIL_ACTUATOR_CONTROLS.controls[16]"),
            "'HIL_ACTUATOR_CONTROLS.controls[16]' at character 32: the index of HIL_ACTUATOR_CONTROLS.controls is 0 to 15");
  EXPECT_EQ(error_of("ATTITUDE.roll[0]"), "'ATTITUDE.roll[0]' at character 14: ATTITUDE.roll is not an array");
  EXPECT_EQ(error_of("STATUSTEXT.text"), "'STATUSTEXT.text' at character 12: STATUSTEXT.text is text, not a number");
  EXPECT_EQ(error_of("ATTITUDE.roll/0"), "'ATTITUDE.roll/0' at character 15: a division by zero");
  EXPECT_EQ(error_of("ATTITUDE.roll*1e999"), "'ATTITUDE.roll*1e999' at character 15: '1e999' is not a finite number");
  EXPECT_EQ(error_of("ATTITUDE.roll*nan"), "'ATTITUDE.roll*nan' at character 15: 'nan' is neither MESSAGE.field nor a function "
                                           "(degrees, radians, abs, sqrt)");
  EXPECT_EQ(error_of("cos(ATTITUDE.roll)"), "'cos(ATTITUDE.roll)' at character 1: no function 'cos' (there are degrees, radians, abs, sqrt)");
  EXPECT_EQ(error_of("(ATTITUDE.roll"), "'(ATTITUDE.roll' at character 1: '(' without its ')'");
  EXPECT_EQ(error_of("ATTITUDE.roll)"), "'ATTITUDE.roll)' at character 14: unexpected ')' (expected an operator + - * / or the end)");
  EXPECT_EQ(error_of("ATTITUDE.roll,,ATTITUDE.yaw"), "'ATTITUDE.roll,,ATTITUDE.yaw' at character 15: an empty series (two commas, or one at an end)");
  EXPECT_EQ(error_of(""), "'' at character 1: an empty series (two commas, or one at an end)");
  EXPECT_EQ(error_of("2*3"), "'2*3' at character 1: the series names no field (MESSAGE.field)");
  EXPECT_EQ(error_of("ATTITUDE.roll 2"), "'ATTITUDE.roll 2' at character 15: unexpected '2' (expected an operator + - * / or the end)");
  EXPECT_EQ(error_of("ATTITUDE.roll*1.2.3"), "'ATTITUDE.roll*1.2.3' at character 15: '1.2.3' is not a number");
  EXPECT_EQ(error_of("ATTITUDE.roll\x01"), "'ATTITUDE.roll\x01' at character 14: a character that is not printable ASCII (byte 1)");
}

TEST(FieldExpression, EverythingThatGrowsWithTheInputIsBounded) {
  EXPECT_EQ(error_of(std::string(1001, ' ')).substr(0, 5), "'    ");
  EXPECT_NE(error_of(std::string(1001, ' ')).find("at character 1001: longer than 1000 characters"), std::string::npos);
  std::string deep = "ATTITUDE.roll";
  for (int i = 0; i < 30; ++i) deep = "(" + deep + ")";
  EXPECT_NE(error_of(deep).find("at character 25: nested too deep (more than 24 parentheses, calls and signs)"), std::string::npos)
      << error_of(deep);
  EXPECT_NE(error_of(std::string(40, '-') + "ATTITUDE.roll").find("nested too deep"), std::string::npos);
  std::string many = "ATTITUDE.roll";
  for (int i = 0; i < 120; ++i) many += "+1";
  EXPECT_NE(error_of(many).find("the series is too long (more than 200 numbers, fields and operations)"), std::string::npos)
      << error_of(many);
  std::string series = "ATTITUDE.roll";
  for (int i = 0; i < 8; ++i) series += ",ATTITUDE.roll";
  EXPECT_NE(error_of(series).find("more than 8 series in one plot"), std::string::npos) << error_of(series);
  // Within the bounds: a long sum evaluates.
  std::string sum = "ATTITUDE.roll";
  for (int i = 0; i < 90; ++i) sum += "+1";
  auto spec = parse_field_plot(sum, messages());
  ASSERT_TRUE(spec) << spec.error().message;
  EXPECT_DOUBLE_EQ(spec->series[0].evaluate(frame_of(msg::Attitude{}).payload.data()), 90.0);
}

}  // namespace
}  // namespace hitl::report
