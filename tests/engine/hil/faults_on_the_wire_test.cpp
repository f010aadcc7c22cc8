// The session's faults as the flight stack sees them (docs/faults.md): a stand-in board on
// loopback stamps each datagram's arrival and reads HIL_SENSOR and HIL_GPS off it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "base/mavlink/frame_parser.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/tlog.h"
#include "tests/engine/hil/wire_board.h"

namespace hitl::hil {
namespace {

namespace msg = mavlink::msg;
using test_wire::Board;
using test_wire::Running;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

TEST(FaultsOnTheWire, GpsLossSendsNoHilGpsInItsWindowAndHilGpsAgainAfter) {
  Board board;
  Running run(board, {"gps-loss@0.5+0.5"});
  const auto got = board.receive_until(1.5, 10);
  int before = 0, during = 0, after = 0;
  for (const auto& a : got) {
    if (!a.gps) continue;
    if (a.gps_sim_s() < 0.5) ++before;
    else if (a.gps_sim_s() < 1.0 - 1e-6) ++during;
    else ++after;
  }
  EXPECT_GT(before, 10);  // 30 Hz
  EXPECT_EQ(during, 0);
  EXPECT_GT(after, 10);
  const auto s = run.snapshot();
  ASSERT_EQ(s.faults.size(), 1u);
  EXPECT_NEAR(s.faults[0].start_s, 0.5, 1e-9);
  EXPECT_NEAR(*s.faults[0].end_s, 1.0, 1e-9);
}

TEST(FaultsOnTheWire, ImuBiasShiftsHilSensorAccelByTheBias) {
  Board board;
  Running run(board, {"imu-bias:0.5,-0.3,0.2@0.5"}, /*noise=*/false);
  const auto got = board.receive_until(1.0, 10);
  Eigen::Vector3d before = Eigen::Vector3d::Zero(), after = Eigen::Vector3d::Zero();
  int nb = 0, na = 0;
  for (const auto& a : got) {
    if (a.sim_s < 0.1 || !a.sensor) continue;  // settled on the gear
    const Eigen::Vector3d accel_FRD_m_s2(a.sensor->xacc, a.sensor->yacc, a.sensor->zacc);
    if (a.sim_s < 0.5 - 1e-6) before += accel_FRD_m_s2, ++nb;
    else after += accel_FRD_m_s2, ++na;
  }
  ASSERT_GT(nb, 50);
  ASSERT_GT(na, 50);
  const Eigen::Vector3d shift = after / na - before / nb;
  EXPECT_NEAR(shift.x(), 0.5, 1e-3);
  EXPECT_NEAR(shift.y(), -0.3, 1e-3);
  EXPECT_NEAR(shift.z(), 0.2, 1e-3);
}

TEST(FaultsOnTheWire, HilDelayArrivesLaterByTheSettingWithoutLateTicks) {
  Board board;
  Running run(board, {"hil-delay:20@1+1"});
  const auto got = board.receive_until(2.5, 10);
  std::vector<double> base, delayed;
  for (const auto& a : got) {
    if (a.sim_s < 0) continue;
    const double offset_s = a.wall_s - a.sim_s;  // arrival against the simulated clock (speed 1)
    if (a.sim_s > 0.3 && a.sim_s < 0.95) base.push_back(offset_s);
    if (a.sim_s > 1.1 && a.sim_s < 1.9) delayed.push_back(offset_s);
  }
  ASSERT_GT(base.size(), 100u);
  ASSERT_GT(delayed.size(), 150u);
  const double measured_ms = (median(delayed) - median(base)) * 1e3;
  std::printf("hil-delay:20 measured %.3f ms at the receiver (median over %zu datagrams)\n", measured_ms, delayed.size());
  EXPECT_NEAR(measured_ms, 20.0, 1.0);
  // Order kept, nothing lost, and the loop kept its pace.
  int missing = 0;
  for (std::size_t i = 1; i < got.size(); ++i)
    if (got[i].sim_s > 0 && got[i - 1].sim_s > 0 && std::abs(got[i].sim_s - got[i - 1].sim_s - 0.004) > 1e-6) ++missing;
  EXPECT_EQ(missing, 0);
  const auto s = run.snapshot();
  EXPECT_LE(s.late_ticks, 2u) << "the 250 Hz loop must not wait for the held datagrams";
  EXPECT_GT(s.hil_link_faults.delayed, 200u);
}

TEST(FaultsOnTheWire, VioDelayArrivesLaterByTheSettingAtTheVioServerOnlyOnThatLink) {
  Board board, vio;
  Running run(board, {"vio-delay:20@1+1", "vio-dup:1@2.2"}, true, "", test_wire::vio_to(vio));
  const auto got = vio.receive_until(2.8, 10);
  std::vector<double> base, delayed;
  int duplicated = 0;
  double last_sim_s = -1;
  for (const auto& a : got) {
    if (!a.odometry) continue;
    const double offset_s = a.wall_s - a.sim_s;
    if (a.sim_s > 0.3 && a.sim_s < 0.95) base.push_back(offset_s);
    if (a.sim_s > 1.1 && a.sim_s < 1.9) delayed.push_back(offset_s);
    if (a.sim_s == last_sim_s) ++duplicated;
    last_sim_s = a.sim_s;
  }
  ASSERT_GT(base.size(), 15u);
  ASSERT_GT(delayed.size(), 20u);
  const double measured_ms = (median(delayed) - median(base)) * 1e3;
  std::printf("vio-delay:20 measured %.3f ms at the VIO server (median over %zu ODOMETRY)\n", measured_ms, delayed.size());
  EXPECT_NEAR(measured_ms, 20.0, 1.0);
  EXPECT_GT(duplicated, 10);  // vio-dup:1 from 2.2 s: every ODOMETRY twice
  const auto s = run.snapshot();
  EXPECT_GT(s.vio_link_faults.delayed, 25u);
  EXPECT_EQ(s.hil_link_faults.delayed, 0u);  // the HIL link untouched
}

TEST(FaultsOnTheWire, HilDropHalfLosesAboutHalfTheDatagrams) {
  Board board;
  Running run(board, {"hil-drop:0.5@0.5+1"});
  const auto got = board.receive_until(2.0, 10);
  int in_window = 0;
  for (const auto& a : got)
    if (a.sim_s >= 0.5 - 1e-6 && a.sim_s < 1.5 - 1e-6) ++in_window;
  // 250 datagrams in the window; dropped each with p = 0.5: 125 +- 3 sigma (sigma 7.9).
  EXPECT_GT(in_window, 125 - 24);
  EXPECT_LT(in_window, 125 + 24);
  const auto s = run.snapshot();
  EXPECT_EQ(s.hil_link_faults.dropped + static_cast<uint64_t>(in_window), 250u);
}

TEST(FaultsOnTheWire, TheRecordingSaysWhatWasInjectedWhen) {
  const std::string path = ::testing::TempDir() + "faults_recording.tlog";
  {
    Board board;
    Running run(board, {"gps-loss@0.5+0.5"}, true, path);
    board.receive_until(1.5, 10);
  }
  auto reader = mavlink::TlogReader::open(path);
  ASSERT_TRUE(reader) << reader.error().message;
  const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  std::vector<std::pair<uint8_t, std::string>> said;  // sysid, text
  mavlink::TlogRecord record;
  while (reader->next(record)) {
    parser.parse_datagram(record.frame, [&](const mavlink::Frame& f) {
      if (!f.is<msg::Statustext>()) return;
      const auto st = f.as<msg::Statustext>();
      std::string text(st.text.data(), strnlen(st.text.data(), st.text.size()));
      if (text.find(" fault ") != std::string::npos) said.emplace_back(f.sysid, text);  // not the IMU's noise statement
    });
  }
  ASSERT_EQ(said.size(), 2U);
  EXPECT_EQ(said[0].first, kSimulatorSystemId);
  EXPECT_EQ(said[0].second, "t=0.500 s fault gps-loss started (0.5 s)");
  EXPECT_EQ(said[1].second, "t=1.000 s fault gps-loss ended");
}

TEST(FaultsOnTheWire, TheRecordingHoldsWhatTheBoardWasSentNotWhatHilDropDropped) {
  const std::string path = ::testing::TempDir() + "faults_dropped.tlog";
  {
    Board board;
    Running run(board, {"hil-drop:1"}, true, path);
    EXPECT_TRUE(board.receive_until(0.5, 1.0).empty());  // everything dropped
  }
  auto reader = mavlink::TlogReader::open(path);
  ASSERT_TRUE(reader) << reader.error().message;
  const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  int hil_sensor = 0;
  mavlink::TlogRecord record;
  while (reader->next(record))
    parser.parse_datagram(record.frame, [&](const mavlink::Frame& f) { hil_sensor += f.is<msg::HilSensor>() ? 1 : 0; });
  EXPECT_EQ(hil_sensor, 0);
}

}  // namespace
}  // namespace hitl::hil
