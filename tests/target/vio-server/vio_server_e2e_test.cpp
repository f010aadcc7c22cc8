// The real voxl-hitl-vio-server over loopback UDP. The test plays both ends: hitl sim sending
// ODOMETRY at 250 Hz, and voxl-vision-hub (plus an inspector on hitl_vio_extended) connecting to
// the MPA pipes the way libmodal_pipe's client does and reading whole records. Every field of
// every record is checked against the ODOMETRY it came from.
// Here the readers: voxl-vision-hub over the pipe and in FIFO mode (the en_hitl reader); the
// server's edges are in vio_server_edges_e2e_test.cpp.
#include <gtest/gtest.h>
#include <signal.h>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/mavlink_peer.h"
#include "tests/target/vio-server/vio_server_run.h"

namespace hitl::vio {
namespace {

using namespace e2e_test;

TEST(VioServerE2E, VisionHubReadsEveryFieldOfEveryPoseAt250Hz) {
  ServerRun run;
  auto server = run.start();
  std::string error;
  auto hub = test::MpaClient::connect(run.vio_pipe(), "voxl-vision-hub", error);
  ASSERT_TRUE(hub.connected()) << error << "\n" << server->err();
  auto inspector = test::MpaClient::connect(run.extended_pipe(), "voxl-inspect-vio", error);
  ASSERT_TRUE(inspector.connected()) << error;
  RecordReader<VioData> hub_reader(hub);
  RecordReader<ExtVioData> ext_reader(inspector);

  const int64_t t_start_ns = monotonic_ns();
  test::MavlinkPeer sim(0, run.port(), 250, 197);
  std::atomic<int> next{0};
  sim.start_paced(kRate_hz, 4000ms, [&](test::MavlinkPeer& p) { p.send(odometry_number(next++)); });
  std::this_thread::sleep_for(4200ms);
  sim.stop();
  const int sent = next.load();
  ASSERT_GT(sent, 500);
  EXPECT_TRUE(eventually([&] { return hub_reader.count() >= static_cast<std::size_t>(sent); }, 10s));
  EXPECT_TRUE(eventually([&] { return ext_reader.count() >= static_cast<std::size_t>(sent); }, 10s));
  hub_reader.stop();
  ext_reader.stop();
  const int64_t t_end_ns = monotonic_ns();

  // Loopback loses nothing; allow a little for a starved machine all the same.
  const auto records = hub_reader.records();
  EXPECT_GE(records.size(), static_cast<std::size_t>(sent * 0.95)) << "sent " << sent;
  std::map<int, int> seen;
  int64_t previous_ns = 0;
  for (const VioData& v : records) {
    const int i = static_cast<int>(v.T_imu_wrt_vio[0]);
    ASSERT_GE(i, 0);
    ASSERT_LT(i, sent);
    ++seen[i];
    expect_record_matches(v, i);
    // CLOCK_MONOTONIC of the board (here: this machine) when the pose arrived, in order.
    EXPECT_GT(v.timestamp_ns, previous_ns);
    EXPECT_GE(v.timestamp_ns, t_start_ns);
    EXPECT_LE(v.timestamp_ns, t_end_ns);
    previous_ns = v.timestamp_ns;
  }
  for (const auto& [i, n] : seen) EXPECT_EQ(n, 1) << "ODOMETRY " << i << " published " << n << " times";

  // The rate, from the records' own timestamps: poses counted over the sending window.
  ASSERT_GE(records.size(), 2u);
  const double span_s = (records.back().timestamp_ns - records.front().timestamp_ns) / 1e9;
  const double rate_hz = (records.size() - 1) / span_s;
  std::cout << "[ measured ] sent " << sent << " ODOMETRY, hitl_vio read " << records.size() << " records, "
            << seen.size() << " distinct, rate " << rate_hz << " Hz from the record timestamps\n";
  EXPECT_GT(rate_hz, 150.0) << records.size() << " records in " << span_s << " s";
  EXPECT_LT(rate_hz, 400.0) << records.size() << " records in " << span_s << " s";

  // hitl_vio_extended: the same vio_data_t, and last_cam_frame_id counting the poses.
  const auto ext = ext_reader.records();
  EXPECT_GE(ext.size(), static_cast<std::size_t>(sent * 0.95));
  for (std::size_t k = 0; k < ext.size(); ++k) {
    const int i = static_cast<int>(ext[k].v.T_imu_wrt_vio[0]);
    expect_record_matches(ext[k].v, i);
    EXPECT_EQ(ext[k].last_cam_timestamp_ns, ext[k].v.timestamp_ns);
    if (k > 0) {
      EXPECT_EQ(ext[k].last_cam_frame_id, ext[k - 1].last_cam_frame_id + 1);
    }
    EXPECT_EQ(ext[k].n_total_features, 0u);
  }

  server->signal(SIGTERM);
  EXPECT_EQ(server->wait(20s), 0) << server->err();
}

TEST(VioServerE2E, VisionHubFifoModeServesTheEnHitlReader) {
  // voxl-vision-hub's en_hitl reader (state_manager.c): open("/run/mpa/hitl_vio", O_RDWR), flush
  // what is waiting, then read(fd, &d, sizeof(vio_data_t)) in a loop.
  ServerRun run;
  auto server = run.start({"--vision-hub-fifo"});
  const std::string fifo = run.mpa_dir() + "hitl_vio";
  struct stat st{};
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0) << server->err();
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_TRUE(fs::exists(run.extended_pipe() + "request")) << "hitl_vio_extended stays an MPA pipe";
  test::MavlinkPeer sim(0, run.port(), 250, 197);
  for (int i = 0; i < 10; ++i) sim.send(odometry_number(i));  // before vision-hub starts: flushed
  ASSERT_TRUE(eventually([&] {
    const auto r = run.status(true);
    return r.exit_code == 0 && nlohmann::json::parse(r.out)["published"].get<int>() == 10;
  }));

  const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  char flush[65536];
  EXPECT_EQ(::read(fd, flush, sizeof flush), static_cast<ssize_t>(10 * sizeof(VioData)));
  std::atomic<int> next{100};
  sim.start_paced(kRate_hz, 1000ms, [&](test::MavlinkPeer& p) { p.send(odometry_number(next++)); });
  std::vector<VioData> records;
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (std::chrono::steady_clock::now() < deadline && (records.size() < 200 || next < 340)) {
    pollfd pfd{fd, POLLIN, 0};
    if (::poll(&pfd, 1, 100) <= 0) continue;
    VioData v;
    const ssize_t n = ::read(fd, &v, sizeof v);
    if (n < 0) continue;
    ASSERT_EQ(n, static_cast<ssize_t>(sizeof v)) << "records arrive whole";
    records.push_back(v);
  }
  sim.stop();
  ASSERT_GE(records.size(), 200u);
  for (const VioData& v : records) expect_record_matches(v, static_cast<int>(v.T_imu_wrt_vio[0]));
  const auto status = run.status(false);
  EXPECT_NE(status.out.find("hitl_vio (vio_data_t, FIFO): readers unknown"), std::string::npos) << status.out;

  server->signal(SIGTERM);
  EXPECT_EQ(server->wait(20s), 0) << server->err();
  ::close(fd);
  EXPECT_FALSE(fs::exists(fifo));
}

}  // namespace
}  // namespace hitl::vio
