// PX4's ULog merged onto a recording: its estimate on the simulator's clock against the truth, the
// offset and the lag measured, the ULog found beside FILE.tlog, and the ULogs that cannot be merged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "engine/report/html.h"
#include "engine/report/parameters.h"
#include "engine/report/plots.h"
#include "engine/report/px4_estimate.h"
#include "tests/support/ulog_writer.h"

namespace hitl::report {
namespace {
namespace msg = mavlink::msg;
using test::ULogWriter;

constexpr uint64_t kEpoch_us = 1'700'000'000'000'000;

/// Height from home of the flight both logs describe: at rest to 2 s, a 1 m/s climb to 2.5 m.
double height_m(double t_s) { return std::clamp(t_s - 2.0, 0.0, 2.5); }

/// A hitl sim recording of that flight: HIL_SENSOR every 4 ms, truth (body origin, 0.22 m at rest) each 20 ms.
void write_tlog(const std::string& path, double seconds) {
  auto writer = mavlink::TlogWriter::open(path).value();
  mavlink::FrameEncoder enc(kSimulatorSystemId, 1);
  for (uint64_t k = 0; k * 0.004 <= seconds; ++k) {
    const uint64_t t_us = k * 4000;
    mavlink::FrameBuffer buf;
    msg::HilSensor s;
    s.time_usec = t_us;
    writer.write(kEpoch_us + t_us, {buf.data(), enc.encode(s, buf)});
    if (k % 5 != 0) continue;
    msg::Odometry truth;
    truth.time_usec = t_us;
    truth.x = 1.0F;
    truth.z = static_cast<float>(-(0.22 + height_m(static_cast<double>(t_us) * 1e-6)));
    truth.q = {1, 0, 0, 0};
    truth.estimator_type = static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap);
    writer.write(kEpoch_us + t_us, {buf.data(), enc.encode(truth, buf)});
  }
  writer.flush();
}

/// PX4's ULog of the same flight at 50 Hz on the simulator's clock (+ `clock_offset_us`): its
/// estimate 0.1 m north of the truth and 0.05 m high, following the truth's height `lag_s` later.
ULogWriter px4_ulog(double seconds, double lag_s, int64_t clock_offset_us = 0) {
  ULogWriter w;
  w.flag_bits();
  w.format("vehicle_local_position:uint64_t timestamp;float x;float y;float z;bool xy_valid;bool z_valid;uint8_t[6] _padding0;");
  w.format("vehicle_attitude:uint64_t timestamp;float[4] q;");
  w.info("uint32_t ver_sw_release", ULogWriter::raw(uint32_t{0x011000FF}));
  w.subscribe(0, "vehicle_local_position");
  w.subscribe(1, "vehicle_attitude");
  for (uint64_t k = 1; k * 0.02 <= seconds; ++k) {
    const double t_s = static_cast<double>(k) * 0.02;
    const auto t_us = static_cast<uint64_t>(static_cast<int64_t>(k * 20'000) + clock_offset_us);
    const float z = static_cast<float>(-(height_m(t_s - lag_s) + 0.05));
    w.data(0, ULogWriter::raw(t_us) + ULogWriter::raw(1.1F) + ULogWriter::raw(0.0F) + ULogWriter::raw(z) + std::string("\1\1", 2));
    w.data(1, ULogWriter::raw(t_us) + ULogWriter::raw(1.0F) + std::string(12, '\0'));
  }
  return w;
}

std::string write_file(const std::string& path, const std::string& bytes) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(Px4Estimate, PlacedOnTheSimulatorsClockWithItsOffsetAndLagAgainstTruth) {
  const std::string dir = ::testing::TempDir() + "px4_estimate/";
  std::filesystem::create_directories(dir);
  write_tlog(dir + "flight.tlog", 6.0);
  const std::string ulog = write_file(dir + "px4.ulg", px4_ulog(6.0, 0.040).text());
  auto log = read_flight_log(dir + "flight.tlog");
  ASSERT_TRUE(log) << log.error().message;
  auto px4 = read_px4_estimate(ulog, *log);
  ASSERT_TRUE(px4) << px4.error().message;
  EXPECT_EQ(px4->version, "v1.16.0");
  EXPECT_GT(px4->position.size(), 250u);
  EXPECT_NEAR(px4->position.t_s.front(), 0.02, 1e-9) << "a ULog timestamp is the simulator's time_usec";
  ASSERT_GT(px4->minus_truth.size(), 250u);
  EXPECT_NEAR(px4->mean_offset_NED_m[0], 0.1, 1e-3);
  EXPECT_NEAR(px4->mean_offset_NED_m[1], 0.0, 1e-6);
  EXPECT_NEAR(px4->mean_offset_NED_m[2], -0.05, 0.02) << "0.05 m high, the 40 ms lag on the climb aside";
  ASSERT_TRUE(px4->lag_s);
  EXPECT_NEAR(*px4->lag_s, 0.040, 0.0041) << "within one simulator step";
  EXPECT_EQ(px4->attitude.size(), px4->position.size());
  // The page: PX4's altitude against the truth, the offset, PX4's attitude beside the others.
  log->px4 = *px4;
  std::map<std::string, std::size_t> series;
  for (const auto& p : plots_of(*log)) series[p.id] = p.series.size();
  EXPECT_EQ(series["px4-altitude"], 2u);
  EXPECT_EQ(series["px4-offset"], 3u);
  EXPECT_EQ(series["attitude-roll"], 2u) << "truth and PX4 (no ATTITUDE in this recording)";
}

TEST(Px4Estimate, AtRestThereIsNoLagToFitAndNoneIsClaimed) {
  const std::string dir = ::testing::TempDir() + "px4_rest/";
  std::filesystem::create_directories(dir);
  write_tlog(dir + "rest.tlog", 1.9);  // before the climb
  const std::string ulog = write_file(dir + "rest.ulg", px4_ulog(1.9, 0).text());
  auto log = read_flight_log(dir + "rest.tlog");
  ASSERT_TRUE(log);
  auto px4 = read_px4_estimate(ulog, *log);
  ASSERT_TRUE(px4) << px4.error().message;
  EXPECT_FALSE(px4->lag_s);
  EXPECT_NE(std::find(px4->notes.begin(), px4->notes.end(), "no lag fitted: the truth's height changed less than 0.5 m (nothing to fit it on)"),
            px4->notes.end());
  EXPECT_NEAR(px4->mean_offset_NED_m[2], -0.05, 1e-6) << "the offset still is";
}

TEST(Px4Estimate, AULogOfAnotherTimeOrALogWithoutASimulatorClockIsRefusedNamed) {
  const std::string dir = ::testing::TempDir() + "px4_other/";
  std::filesystem::create_directories(dir);
  write_tlog(dir + "flight.tlog", 2.0);
  const std::string other = write_file(dir + "other.ulg", px4_ulog(2.0, 0, 3'600'000'000).text());
  auto log = read_flight_log(dir + "flight.tlog");
  ASSERT_TRUE(log);
  auto px4 = read_px4_estimate(other, *log);
  ASSERT_FALSE(px4);
  EXPECT_NE(px4.error().message.find("'" + other + "' is of another time"), std::string::npos) << px4.error().message;
  const std::string junk = write_file(dir + "junk.ulg", "not a ulog at all");
  px4 = read_px4_estimate(junk, *log);
  ASSERT_FALSE(px4);
  EXPECT_NE(px4.error().message.find("is not a ULog"), std::string::npos) << px4.error().message;
  log->simulated_time = false;
  px4 = read_px4_estimate(other, *log);
  ASSERT_FALSE(px4);
  EXPECT_NE(px4.error().message.find("no simulator's clock"), std::string::npos) << px4.error().message;
}

TEST(Px4Estimate, TheNewestULogBesideTheRecordingIsFound) {
  const std::string dir = ::testing::TempDir() + "px4_find/";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  EXPECT_FALSE(find_px4_ulog(dir + "s.tlog"));
  const std::string older = write_file(dir + "s.px4/log/2026-11-28/23_59_00.ulg", "x");
  write_file(dir + "s.px4/log/2026-11-28/notes.txt", "not a log");
  const std::string newer = write_file(dir + "s.px4/log/2026-11-29/08_00_00.ulg", "y");
  std::filesystem::last_write_time(older, std::filesystem::last_write_time(newer) - std::chrono::seconds(60));
  EXPECT_EQ(find_px4_ulog(dir + "s.tlog").value_or(""), newer);
  EXPECT_FALSE(find_px4_ulog(dir + "t.tlog")) << "another recording's folder";
}

TEST(Px4Estimate, EkfInnovationsAndTestRatiosArePlottedOnTheSameClockZeroSourcesNamed) {
  // PX4's estimator_innovations and _test_ratios (here at 2 Hz): GPS and barometer
  // fused, vision not (its innovations stay 0).
  const std::string dir = ::testing::TempDir() + "px4_innovations/";
  std::filesystem::create_directories(dir);
  write_tlog(dir + "flight.tlog", 6.0);
  ULogWriter w = px4_ulog(6.0, 0.040);
  const std::string innovations_format =
      "uint64_t timestamp;uint64_t timestamp_sample;float[2] gps_hvel;float gps_vvel;float[2] gps_hpos;float gps_vpos;"
      "float[2] ev_hvel;float ev_vvel;float[2] ev_hpos;float ev_vpos;float rng_vpos;float baro_vpos;float[2] aux_hvel;"
      "float[2] flow;float heading;float[3] mag_field;float[3] gravity;float[2] drag;float airspeed;float beta;float hagl;"
      "float hagl_rate;";
  w.format("estimator_innovations:" + innovations_format);
  w.format("estimator_innovation_test_ratios:" + innovations_format);
  w.subscribe(2, "estimator_innovations");
  w.subscribe(3, "estimator_innovation_test_ratios");
  for (uint64_t k = 1; k <= 12; ++k) {
    const uint64_t t_us = k * 500'000;
    auto record = [&](float scale) {
      std::string b = ULogWriter::raw(t_us) + ULogWriter::raw(t_us);
      auto f = [&](float v) { b += ULogWriter::raw(v * scale); };
      f(0.1F), f(-0.2F), f(0.05F);                 // gps_hvel, gps_vvel
      f(0.3F), f(0.4F), f(-0.5F);                  // gps_hpos, gps_vpos
      for (int i = 0; i < 6; ++i) f(0);            // ev_*: not fused
      f(0), f(0.25F);                              // rng_vpos, baro_vpos
      for (int i = 0; i < 4; ++i) f(0);            // aux_hvel, flow
      f(0.01F);                                    // heading (rad)
      f(0.002F), f(0.003F), f(0.004F);             // mag_field
      for (int i = 0; i < 9; ++i) f(0);            // gravity .. hagl_rate
      return b;
    };
    w.data(2, record(1.0F));
    w.data(3, record(2.0F));
  }
  const std::string ulog = write_file(dir + "px4.ulg", w.text());
  auto log = read_flight_log(dir + "flight.tlog");
  ASSERT_TRUE(log) << log.error().message;
  auto px4 = read_px4_estimate(ulog, *log);
  ASSERT_TRUE(px4) << px4.error().message;
  EXPECT_EQ(px4->innovations_missing, "");
  std::map<std::string, const Px4Innovation*> by_name;
  for (const auto& i : px4->innovations) by_name[i.name] = &i;
  for (const char* name : {"GPS velocity north", "GPS velocity east", "barometer height", "heading"})
    ASSERT_TRUE(by_name.count(name)) << name;
  EXPECT_EQ(by_name["GPS velocity north"]->value.size(), 12u);
  EXPECT_NEAR(by_name["GPS velocity north"]->value.t_s[0], 0.5, 1e-9) << "the simulator's clock";
  EXPECT_NEAR(by_name["GPS velocity east"]->value.value[0], -0.2, 1e-6);
  EXPECT_NEAR(by_name["barometer height"]->value.value[0], 0.25, 1e-6);
  EXPECT_NEAR(by_name["heading"]->value.value[0], 0.01 * 180 / M_PI, 1e-4) << "in degrees";
  EXPECT_EQ(px4->innovations.size(), 11u);  // GPS 6, barometer, magnetometer 3, heading
  EXPECT_FALSE(by_name.count("vision velocity north")) << "0 throughout: not fused";
  EXPECT_NE(std::find(px4->innovations_zero.begin(), px4->innovations_zero.end(), "vision velocity north"), px4->innovations_zero.end());
  std::map<std::string, double> ratio;
  for (const auto& r : px4->test_ratios) ratio[r.name] = r.value.value.at(0);
  EXPECT_NEAR(ratio["GPS position"], 0.6, 1e-6);
  EXPECT_NEAR(ratio["magnetometer"], 0.004, 1e-6);
  // The plots: one per kind of innovation fused and the test ratios, in the report's order.
  log->px4 = *px4;
  std::map<std::string, std::vector<std::string>> series;
  std::vector<std::string> order;
  for (const auto& p : plots_of(*log, {2500, 1e-4, true})) {  // with the plots this log lacks, in their places
    order.push_back(p.id);
    for (const auto& s : p.series) series[p.id].push_back(s.title);
  }
  EXPECT_EQ(series["px4-innovations-velocity"], (std::vector<std::string>{"GPS velocity north", "GPS velocity east", "GPS velocity down"}));
  EXPECT_EQ(series["px4-innovations-height"], (std::vector<std::string>{"GPS height", "barometer height"}));
  EXPECT_EQ(series["px4-innovations-magnetometer"].size(), 3u);
  EXPECT_EQ(series["px4-test-ratios"].size(), 7u);  // GPS x4, barometer, magnetometer, heading
  const auto at = [&](const std::string& id) { return std::find(order.begin(), order.end(), id) - order.begin(); };
  EXPECT_LT(at("ekf"), at("px4-innovations-velocity"));
  EXPECT_LT(at("px4-innovations-heading"), at("px4-test-ratios"));
}

TEST(Px4Estimate, AULogWithoutInnovationsSaysSoInThePlotsPlace) {
  const std::string dir = ::testing::TempDir() + "px4_no_innovations/";
  std::filesystem::create_directories(dir);
  write_tlog(dir + "flight.tlog", 3.0);
  auto log = read_flight_log(dir + "flight.tlog");
  ASSERT_TRUE(log);
  auto px4 = read_px4_estimate(write_file(dir + "px4.ulg", px4_ulog(3.0, 0).text()), *log);
  ASSERT_TRUE(px4) << px4.error().message;
  EXPECT_EQ(px4->innovations_missing, "estimator_innovations: not in this log");
  log->px4 = *px4;
  std::map<std::string, std::string> lacks;
  for (const auto& p : plots_of(*log, {2500, 1e-4, true})) lacks[p.id] = p.lacks;
  EXPECT_EQ(lacks["px4-innovations"], "this log has no PX4's ULog estimator_innovations (estimator_innovations: not in this log)");
  EXPECT_EQ(lacks["px4-test-ratios"], "this log has no PX4's ULog estimator_innovation_test_ratios");
}

TEST(Px4Estimate, TheULogsParametersAndLoggedDefaultsGiveTheNonDefaultTable) {
  // The real PX4 v1.16.0 SITL ULog: 924 parameters, 70 logged defaults ('Q': PX4 logs one only for a
  // parameter whose value differs from it).
  const std::string dir = ::testing::TempDir() + "px4_params/";
  std::filesystem::create_directories(dir);
  write_tlog(dir + "flight.tlog", 1.0);
  auto log = read_flight_log(dir + "flight.tlog");
  ASSERT_TRUE(log);
  Px4Estimate px4;
  px4.path = "px4.ulg";
  px4.parameters = {{"MPC_XY_P", 0.95}, {"SYS_HITL", 1}, {"EKF2_GPS_CTRL", 7}, {"CAL_ACC0_ID", 1310988}};
  px4.parameter_defaults = {{"MPC_XY_P", 0.95}, {"SYS_HITL", 0}};
  log->px4 = px4;
  // No PARAM_VALUE in the recording: the ULog's own values against its defaults.
  auto t = non_default_parameters(*log);
  EXPECT_NE(t.values_from.find("no PARAM_VALUE in this log: PX4's ULog's parameters (4"), std::string::npos) << t.values_from;
  EXPECT_NE(t.defaults_from.find("PX4's ULog px4.ulg"), std::string::npos);
  ASSERT_EQ(t.differ.size(), 1u);
  EXPECT_EQ(t.differ[0].name, "SYS_HITL");
  EXPECT_EQ(t.differ[0].value, 1);
  EXPECT_EQ(t.differ[0].default_value, 0);
  EXPECT_EQ(t.compared, 4u);
  // PARAM_VALUE in the recording wins as the values; a changed one differs from the ULog's start.
  log->parameters = {{"MPC_XY_P", 1.2}, {"SYS_HITL", 0}, {"NOT_IN_PX4", 3}};
  t = non_default_parameters(*log);
  EXPECT_NE(t.values_from.find("PARAM_VALUE in this log (3 parameters"), std::string::npos) << t.values_from;
  ASSERT_EQ(t.differ.size(), 1u);
  EXPECT_EQ(t.differ[0].name, "MPC_XY_P");
  EXPECT_NEAR(t.differ[0].value, 1.2, 1e-9);
  EXPECT_NEAR(t.differ[0].default_value, 0.95, 1e-9);
  EXPECT_EQ(t.without_default, 1u);
  // Without a ULog: the emulated board's defaults, the spec's HITL set.
  log->px4.reset();
  log->parameters = {{"SYS_HITL", 0}, {"CAL_ACC0_ID", 1310988}, {"MPC_XY_P", 1.2}};
  t = non_default_parameters(*log);
  EXPECT_NE(t.defaults_from.find("base/contract/hitl-defaults.params"), std::string::npos) << t.defaults_from;
  ASSERT_EQ(t.differ.size(), 1u);
  EXPECT_EQ(t.differ[0].name, "SYS_HITL");
  EXPECT_EQ(t.differ[0].default_value, 1);
  EXPECT_EQ(t.compared, 2u);
  EXPECT_EQ(t.without_default, 1u) << "MPC_XY_P is not in the HITL set";
  // No parameters at all: the page says so in the table's place.
  log->parameters.clear();
  EXPECT_EQ(non_default_parameters(*log).values_from, "");
  EXPECT_NE(parameters_section(*log).find("no PARAM_VALUE in this log"), std::string::npos);
}

TEST(Px4Estimate, ParamValueIntegersAreDecodedByteWiseAsPx4SendsThem) {
  int32_t id = 1310988;
  float wire = 0;
  std::memcpy(&wire, &id, sizeof wire);
  EXPECT_EQ(param_value_number(wire, 6), 1310988.0);
  EXPECT_EQ(param_value_number(0.5F, 9), 0.5);
  uint32_t small = 200;
  std::memcpy(&wire, &small, sizeof wire);
  EXPECT_EQ(param_value_number(wire, 1), 200.0);
}

}  // namespace
}  // namespace hitl::report
