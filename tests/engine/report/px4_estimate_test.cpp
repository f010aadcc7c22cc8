// PX4's ULog merged onto a recording: its estimate on the simulator's clock against the truth, the
// offset and the lag measured, the ULog found beside FILE.tlog, and the ULogs that cannot be merged.
#include <gtest/gtest.h>

#include <algorithm>
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

}  // namespace
}  // namespace hitl::report
