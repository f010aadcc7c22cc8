// PX4's ULog read: a log real PX4 v1.16.0 SITL wrote under hitl sim --px4 (a 2.5 m hover,
// vehicle_local_position and vehicle_attitude at 10 Hz), logs written here field by field, and
// hostile ones: each a named error or notes, never a crash, a hang or unbounded growth.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>

#include "engine/ulog/ulog.h"
#include "engine/ulog/ulog_format.h"
#include "tests/support/ulog_writer.h"

namespace hitl::ulog {
namespace {

using test::ULogWriter;
const std::string kRealLog = std::string(HITL_SOURCE_DIR) + "/tests/data/px4_v1.16_hover_2.5m.ulg";

Expected<ULogFile> parse(const ULogWriter& w, const std::vector<Request>& requests = {}, const Limits& limits = {}) {
  std::istringstream in(w.text());
  return parse_ulog(in, "test.ulg", requests, limits);
}

/// A log of one topic "pos" (timestamp, x, q[2]) subscribed as id 3, with `n` samples.
ULogWriter pos_log(int n) {
  ULogWriter w;
  w.flag_bits();
  w.format("pos:uint64_t timestamp;float x;float[2] q;uint8_t[3] _padding0;");
  w.info("char[4] ver_sw", "v1.0");
  w.parameter_float("MPC_Z_VEL_MAX_UP", 3.0F);
  w.subscribe(3, "pos");
  for (int k = 0; k < n; ++k)
    w.data(3, ULogWriter::raw(uint64_t(1000 + 4000 * k)) + ULogWriter::raw(float(k)) + ULogWriter::raw(0.5F) +
                  ULogWriter::raw(float(-k)));  // the trailing padding left out, as PX4's logger does
  w.logged('6', 5000, "takeoff detected");
  return w;
}

TEST(ULog, ARealPx4SitlLogGivesItsEstimateInfoAndParameters) {
  const auto t0 = std::chrono::steady_clock::now();
  auto log = read_ulog(kRealLog, {{"vehicle_local_position", {"x", "y", "z", "xy_valid", "z_valid"}, 0},
                                  {"vehicle_attitude", {"q[0]", "q[1]", "q[2]", "q[3]"}, 0}});
  const double parse_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(log) << log.error().message;
  std::printf("[ figures  ] %s: %llu bytes, %llu messages parsed in %.1f ms\n", kRealLog.c_str(),
              static_cast<unsigned long long>(log->bytes), static_cast<unsigned long long>(log->messages), parse_ms);
  EXPECT_EQ(log->version, 1);
  EXPECT_FALSE(log->cut);
  EXPECT_EQ(log->bad_messages, 0u);
  EXPECT_EQ(log->info["sys_name"], "PX4");
  EXPECT_EQ(log->info["ver_sw"].size(), 40u) << "a git hash";
  EXPECT_TRUE(log->parameters.count("MPC_XY_CRUISE"));
  EXPECT_GT(log->parameters.size(), 500u);
  // Its logged defaults ('Q'), only for the 62 parameters whose value differs from one: the system's
  // (bit 0), the current setup's (bit 1), or both in one message.
  EXPECT_EQ(log->parameter_defaults.size(), 62u);
  EXPECT_EQ(log->parameter_defaults["BAT1_N_CELLS"].system, 0.0);
  EXPECT_FALSE(log->parameter_defaults["BAT1_N_CELLS"].current_setup);
  EXPECT_EQ(log->parameters["BAT1_N_CELLS"], 4.0);
  EXPECT_EQ(log->parameter_defaults["CAL_BARO0_PRIO"].system, -1.0);
  EXPECT_EQ(log->parameter_defaults["CAL_BARO0_PRIO"].current_setup, -1.0);
  ASSERT_EQ(log->series.size(), 2u);
  const auto& pos = log->series[0];
  EXPECT_EQ(pos.missing, "");
  ASSERT_GT(pos.size(), 200u) << "10 Hz over the flight";
  for (std::size_t i = 1; i < pos.size(); ++i) ASSERT_GE(pos.timestamp_us[i], pos.timestamp_us[i - 1]) << i;
  // The hover at 2.5 m: the lowest z (NED, up is negative) is about -2.5.
  double min_z = 0;
  for (double z : pos.values[2]) min_z = std::min(min_z, z);
  EXPECT_NEAR(min_z, -2.5, 0.3);
  const auto& att = log->series[1];
  ASSERT_GT(att.size(), 200u);
  for (std::size_t i = 0; i < att.size(); ++i) {
    const double n = std::hypot(std::hypot(att.values[0][i], att.values[1][i]), std::hypot(att.values[2][i], att.values[3][i]));
    ASSERT_NEAR(n, 1.0, 1e-3) << "a unit quaternion, sample " << i;
  }
  EXPECT_GT(log->strings.size(), 0u);
}

TEST(ULog, FieldsAreFoundByTheirFormatsLayoutWithTheTrailingPaddingLeftOut) {
  auto log = parse(pos_log(3), {{"pos", {"x", "q[1]"}, 0}, {"absent", {"x"}, 0}, {"pos", {"nope"}, 0}});
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->info["ver_sw"], "v1.0");
  EXPECT_FLOAT_EQ(static_cast<float>(log->parameters["MPC_Z_VEL_MAX_UP"]), 3.0F);
  EXPECT_EQ(log->topics, std::vector<std::string>{"pos"});
  const auto& s = log->series[0];
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.timestamp_us[2], 9000u);
  EXPECT_DOUBLE_EQ(s.values[0][2], 2.0);
  EXPECT_DOUBLE_EQ(s.values[1][2], -2.0);
  EXPECT_EQ(log->series[1].missing, "not in this log");
  EXPECT_EQ(log->series[2].missing, "its format has no basic field nope");
  ASSERT_EQ(log->strings.size(), 1u);
  EXPECT_EQ(log->strings[0].text, "takeoff detected");
  EXPECT_EQ(log->strings[0].timestamp_us, 5000u);
}

TEST(ULog, NestedFormatsAreLaidOutEvenWhenDefinedAfterTheirUse) {
  ULogWriter w;
  w.format("outer:uint64_t timestamp;inner[2] in;float after;");
  w.format("inner:uint16_t a;uint8_t b;");  // 3 bytes each
  w.subscribe(0, "outer");
  w.data(0, ULogWriter::raw(uint64_t(7)) + std::string(6, '\0') + ULogWriter::raw(1.25F));
  auto log = parse(w, {{"outer", {"after"}, 0}});
  ASSERT_TRUE(log) << log.error().message;
  ASSERT_EQ(log->series[0].size(), 1u);
  EXPECT_DOUBLE_EQ(log->series[0].values[0][0], 1.25);
}

TEST(ULog, NotAULogAndRefusedFlagsAreNamedErrors) {
  std::istringstream text("this is not a log");
  auto r = parse_ulog(text, "/x/y.ulg", {});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::Input);
  EXPECT_NE(r.error().message.find("'/x/y.ulg' is not a ULog"), std::string::npos) << r.error().message;
  ULogWriter w;
  w.flag_bits(0x02);  // an incompatible bit nobody defined
  r = parse(w);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("incompatible ULog flags"), std::string::npos) << r.error().message;
  ULogWriter w2;
  w2.flag_bits(0, 0, 0x80);
  EXPECT_FALSE(parse(w2));
  auto missing = read_ulog("/nonexistent/log.ulg", {});
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/nonexistent/log.ulg"), std::string::npos);
  auto dir = read_ulog("/tmp", {});
  ASSERT_FALSE(dir);
  EXPECT_NE(dir.error().message.find("not a regular file"), std::string::npos);
}

TEST(ULog, ALogCutInTheMiddleOfAMessageKeepsWhatCameBefore) {
  const std::string full = pos_log(5).text();
  for (std::size_t cut : {full.size() - 1, full.size() - 30, std::size_t{17}}) {
    std::istringstream in(full.substr(0, cut));
    auto log = parse_ulog(in, "cut.ulg", {{"pos", {"x"}, 0}});
    ASSERT_TRUE(log) << cut << ": " << log.error().message;
    EXPECT_TRUE(log->cut) << cut;
  }
}

TEST(ULog, AppendedDataIsReadFromItsOffset) {
  // A log that stopped mid-message, then data appended at its end (the crash dump case).
  ULogWriter w;
  const std::size_t flag_at = w.bytes().size();
  w.flag_bits(0x01, 0);
  w.format("pos:uint64_t timestamp;float x;");
  w.subscribe(1, "pos");
  w.data(1, ULogWriter::raw(uint64_t(10)) + ULogWriter::raw(1.0F));
  std::string text = w.text() + std::string("\x20\x00\x44\x01\x00", 5);  // a 'D' header with 3 of its 32 bytes
  const uint64_t appended_at = text.size();
  ULogWriter tail;
  tail.data(1, ULogWriter::raw(uint64_t(20)) + ULogWriter::raw(2.0F));
  text += tail.text().substr(16);  // the messages only, not a second header
  std::memcpy(text.data() + flag_at + 3 + 16, &appended_at, 8);
  std::istringstream in(text);
  auto log = parse_ulog(in, "appended.ulg", {{"pos", {"x"}, 0}});
  ASSERT_TRUE(log) << log.error().message;
  ASSERT_EQ(log->series[0].size(), 2u);
  EXPECT_DOUBLE_EQ(log->series[0].values[0][1], 2.0);
}

TEST(ULog, HostileFormatsAreUnusableNotFatal) {
  ULogWriter w;
  w.format("a:b x;uint64_t timestamp;");  // a cycle: a -> b -> a
  w.format("b:a y;");
  w.format("big:uint64_t timestamp;double[65535] a;double[65535] b;double[65535] c;float x;");  // over 1 MiB
  w.format("bad");
  w.format("bad2:float[0] x;");
  w.format("bad3:float[99999999999] x;");
  w.format("bad4:flo at x;");
  w.subscribe(0, "a");
  w.subscribe(1, "big");
  w.subscribe(1, "big");  // the same id twice
  w.data(0, std::string(50, '\1'));
  w.data(9, std::string(4, '\1'));  // no such subscription
  w.message('Z', "future message type");
  auto log = parse(w, {{"a", {"timestamp"}, 0}, {"big", {"x"}, 0}});
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->series[0].size(), 0u);
  EXPECT_NE(log->series[0].missing, "");
  EXPECT_NE(log->series[1].missing, "");
  EXPECT_EQ(log->unknown_messages, 1u);
  EXPECT_GE(log->bad_messages, 6u);
}

// Found by the fuzzer (fuzz.ulog): a double information value of 1e300 was written by
// std::to_string as 300 digits, past the text limit every other value keeps.
TEST(ULog, NumbersInTheInformationAreShortWhateverTheirSize) {
  ULogWriter w;
  w.flag_bits();
  w.info("double big", ULogWriter::raw(1e300));
  w.info("float small", ULogWriter::raw(-1.5e-30F));
  w.info("uint64_t id", ULogWriter::raw(uint64_t(18446744073709551615ULL)));
  w.info("int32_t n", ULogWriter::raw(int32_t(-42)));
  const auto log = parse(w);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->info.at("big"), "1e+300");
  EXPECT_EQ(log->info.at("small"), "-1.5e-30");
  EXPECT_EQ(log->info.at("id"), "18446744073709551616");  // as a double holds it
  EXPECT_EQ(log->info.at("n"), "-42");
}

TEST(ULog, WhatGrowsWithTheInputIsBoundedAndSaid) {
  ULogWriter w = pos_log(50);
  for (int k = 0; k < 30; ++k) w.logged('6', 1, std::string(5000, 'x'));
  Limits limits;
  limits.max_samples = 10;
  limits.max_strings = 5;
  limits.max_text_bytes = 100;
  auto log = parse(w, {{"pos", {"x"}, 0}}, limits);
  ASSERT_TRUE(log) << log.error().message;
  EXPECT_EQ(log->series[0].size(), 10u);
  EXPECT_EQ(log->strings.size(), 5u);
  EXPECT_EQ(log->strings[1].text.size(), 103u);  // 100 and "..."
  bool said_samples = false, said_strings = false;
  for (const auto& n : log->notes) {
    said_samples = said_samples || n == "40 samples after the first 10";
    said_strings = said_strings || n == "26 logged strings after the first 5";
  }
  EXPECT_TRUE(said_samples);
  EXPECT_TRUE(said_strings);
  limits = {};
  limits.max_bytes = 200;
  log = parse(w, {{"pos", {"x"}, 0}}, limits);
  ASSERT_TRUE(log);
  EXPECT_LE(log->bytes, 200u + 3 + 65535);
}

TEST(ULogFormat, ParsesTypesArraysAndNames) {
  auto f = parse_format("vehicle_attitude:uint64_t timestamp;float[4] q;uint8_t quat_reset_counter;uint8_t[7] _padding0;");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->name, "vehicle_attitude");
  ASSERT_EQ(f->fields.size(), 4u);
  EXPECT_EQ(f->fields[1].count, 4u);
  EXPECT_TRUE(f->fields[1].array);
  EXPECT_FALSE(parse_format("float:float x;")) << "a basic type's name is no message name";
  EXPECT_FALSE(parse_format("m:float[] x;"));
  EXPECT_FALSE(parse_format("m:float x y;"));
  EXPECT_FALSE(parse_format("m:"));
}

}  // namespace
}  // namespace hitl::ulog
