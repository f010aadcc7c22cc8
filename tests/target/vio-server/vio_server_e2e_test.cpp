// The real voxl-hitl-vio-server over loopback UDP. The test plays both ends: hitl sim sending
// ODOMETRY at 250 Hz, and voxl-vision-hub (plus an inspector on hitl_vio_extended) connecting to
// the MPA pipes the way libmodal_pipe's client does and reading whole records. Every field of
// every record is checked against the ODOMETRY it came from.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <time.h>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "target/vio-server/vio_data.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"
#include "tests/target/vio-server/mpa_client.h"

namespace hitl::vio {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using test::Process;

constexpr double kRate_hz = 250.0;

int64_t monotonic_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

/// ODOMETRY number i: every field carries something of i, so each record can be traced back.
mavlink::msg::Odometry odometry_number(int i) {
  mavlink::msg::Odometry m;
  m.time_usec = 1'000'000 + static_cast<uint64_t>(i) * 4000;
  m.frame_id = static_cast<uint8_t>(mavlink::MavFrame::LocalNed);
  m.child_frame_id = static_cast<uint8_t>(mavlink::MavFrame::BodyFrd);
  m.x = static_cast<float>(i);  // the record's identity
  m.y = -0.5f * static_cast<float>(i);
  m.z = -2.0f - 0.001f * static_cast<float>(i);
  const double yaw = 0.01 * i;
  m.q = {float(std::cos(yaw / 2)), 0, 0, float(std::sin(yaw / 2))};
  m.vx = 1.0f + 0.001f * float(i);
  m.vy = -0.25f;
  m.vz = 0.125f;
  m.rollspeed = 0.01f;
  m.pitchspeed = -0.02f;
  m.yawspeed = 0.03f + 0.0001f * float(i);
  for (std::size_t d = 0; d < 6; ++d) {
    m.pose_covariance[kCovarianceDiagonal[d]] = 0.001f * float(d + 1);
    m.velocity_covariance[kCovarianceDiagonal[d]] = 0.01f * float(d + 1);
  }
  m.pose_covariance[1] = 0.5f;  // off-diagonal: not carried
  m.estimator_type = 3;
  m.quality = static_cast<int8_t>(1 + i % 100);
  return m;
}

/// Checks one record against the ODOMETRY it came from; independent closed forms (a yaw rotation).
void expect_record_matches(const VioData& v, int i) {
  SCOPED_TRACE("record of ODOMETRY " + std::to_string(i));
  const auto m = odometry_number(i);
  EXPECT_EQ(v.magic_number, 0x05455524u);
  EXPECT_EQ(v.T_imu_wrt_vio[0], m.x);
  EXPECT_EQ(v.T_imu_wrt_vio[1], m.y);
  EXPECT_EQ(v.T_imu_wrt_vio[2], m.z);
  const double yaw = 0.01 * i;
  const double R[3][3] = {{std::cos(yaw), -std::sin(yaw), 0}, {std::sin(yaw), std::cos(yaw), 0}, {0, 0, 1}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v.R_imu_to_vio[r][c], R[r][c], 2e-6);
  }
  EXPECT_EQ(v.vel_imu_wrt_vio[0], m.vx);  // body frame, as vision-hub's HITL reader expects
  EXPECT_EQ(v.vel_imu_wrt_vio[1], m.vy);
  EXPECT_EQ(v.vel_imu_wrt_vio[2], m.vz);
  EXPECT_EQ(v.imu_angular_vel[0], m.rollspeed);
  EXPECT_EQ(v.imu_angular_vel[1], m.pitchspeed);
  EXPECT_EQ(v.imu_angular_vel[2], m.yawspeed);
  for (std::size_t k = 0; k < 21; ++k) {
    const bool diagonal = k == 0 || k == 6 || k == 11 || k == 15 || k == 18 || k == 20;
    EXPECT_EQ(v.pose_covariance[k], diagonal ? m.pose_covariance[k] : 0.0f) << k;
    EXPECT_EQ(v.velocity_covariance[k], diagonal ? m.velocity_covariance[k] : 0.0f) << k;
  }
  EXPECT_EQ(v.gravity_vector[0], 0.0f);
  EXPECT_EQ(v.gravity_vector[1], 0.0f);
  EXPECT_FLOAT_EQ(v.gravity_vector[2], 9.80665f);
  for (int r = 0; r < 3; ++r) {
    EXPECT_EQ(v.T_cam_wrt_imu[r], 0.0f);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(v.R_cam_to_imu[r][c], r == c ? 1.0f : 0.0f);
  }
  EXPECT_EQ(v.quality, m.quality);
  EXPECT_EQ(v.state, kVioStateOk);
  EXPECT_EQ(v.error_code, 0u);
  EXPECT_EQ(v.n_feature_points, 0);
  EXPECT_EQ(v.frame, kVioFrameBodyAligned);
}

/// A voxl-hitl-vio-server in a temporary directory of its own, on a free loopback port.
class ServerRun {
 public:
  ServerRun() : dir_(test::temp_dir()), port_(test::free_udp_port()) {
    std::ofstream(config_path()) << R"({"receiver_ip": "127.0.0.1", "receiver_port": )" << port_ << "}\n";
  }
  std::vector<std::string> args(std::vector<std::string> extra = {}) const {
    std::vector<std::string> a{HITL_VIO_SERVER_BINARY, "--config", config_path(), "--mpa-dir", mpa_dir(),
                               "--status-file", status_file()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  std::unique_ptr<Process> start(std::vector<std::string> extra = {}) {
    auto p = std::make_unique<Process>(args(std::move(extra)));
    EXPECT_TRUE(p->wait_for_stderr("listening for ODOMETRY", 20s)) << p->err();
    return p;
  }
  test::RunResult status(bool json) const {
    std::vector<std::string> a = args({"--status"});
    if (json) a.push_back("--json");
    Process p(a);
    const int code = p.wait(20s);
    return {code, p.out(), p.err()};
  }
  std::string config_path() const { return dir_ + "/voxl-hitl-vio-server.conf"; }
  std::string mpa_dir() const { return dir_ + "/mpa/"; }
  std::string status_file() const { return dir_ + "/status.json"; }
  std::string vio_pipe() const { return mpa_dir() + "hitl_vio/"; }
  std::string extended_pipe() const { return mpa_dir() + "hitl_vio_extended/"; }
  uint16_t port() const { return port_; }

 private:
  std::string dir_;
  uint16_t port_;
};

/// Reads whole records of type R from a client until told to stop.
template <class R>
class RecordReader {
 public:
  explicit RecordReader(test::MpaClient& client) : client_(client), thread_([this] {
    while (!stop_) {
      R r;
      if (!client_.read_exact(&r, sizeof r, 200ms)) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      records_.push_back(r);
    }
  }) {}
  ~RecordReader() { stop(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return records_.size();
  }
  std::vector<R> records() {
    std::lock_guard<std::mutex> lock(mutex_);
    return records_;
  }

 private:
  test::MpaClient& client_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<R> records_;
  std::thread thread_;
};

template <class F>
bool eventually(F pred, std::chrono::milliseconds timeout = 10s) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    if (pred()) return true;
    std::this_thread::sleep_for(20ms);
  }
  return pred();
}

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

TEST(VioServerE2E, MalformedPacketsAreCountedAndLoggedAndStatusReportsRateAndCounts) {
  ServerRun run;
  auto server = run.start();
  test::MavlinkPeer sim(0, run.port(), 250, 197);
  const std::vector<uint8_t> garbage{'n', 'o', 't', ' ', 'm', 'a', 'v', 'l', 'i', 'n', 'k'};
  for (int k = 0; k < 20; ++k) sim.send_bytes(garbage);
  mavlink::FrameBuffer buf;
  for (int k = 0; k < 5; ++k) {
    const std::size_t n = sim.encoder().encode(odometry_number(k), buf);
    buf[n - 2] ^= 0x5A;  // checksum broken
    sim.send_bytes({buf.data(), n});
  }
  auto invalid = odometry_number(0);
  invalid.q = {0, 0, 0, 0};  // not a rotation: decoded, counted, not published
  sim.send(invalid);
  std::atomic<int> next{0};
  sim.start_paced(kRate_hz, 3000ms, [&](test::MavlinkPeer& p) { p.send(odometry_number(next++)); });

  // While ODOMETRY flows, --status reports its rate (the last second) and the counts.
  std::this_thread::sleep_for(2200ms);
  const auto text = run.status(false);
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("ODOMETRY:"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("25 malformed"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("1 invalid"), std::string::npos) << text.out;
  const auto json_run = run.status(true);
  ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
  const auto doc = nlohmann::json::parse(json_run.out);
  EXPECT_TRUE(doc["running"].get<bool>());
  EXPECT_GT(doc["odometry_rate_hz"].get<double>(), 50.0);  // ~250; generous for a busy machine
  EXPECT_LT(doc["odometry_rate_hz"].get<double>(), 600.0);
  EXPECT_EQ(doc["malformed_datagrams"], 25);
  EXPECT_GE(doc["crc_errors"].get<int>(), 5);
  EXPECT_EQ(doc["invalid_odometry"], 1);
  EXPECT_EQ(doc["listen"], "127.0.0.1:" + std::to_string(run.port()));
  sim.stop();

  EXPECT_TRUE(server->running()) << "malformed input must not stop the server";
  EXPECT_NE(server->err().find("malformed datagram from 127.0.0.1"), std::string::npos) << server->err();
  EXPECT_NE(server->err().find("unpublishable ODOMETRY: ODOMETRY quaternion has length 0"), std::string::npos)
      << server->err();
  EXPECT_NE(server->err().find("further malformed datagrams are counted"), std::string::npos) << server->err();
  EXPECT_TRUE(eventually([&] {
    const auto r = run.status(true);
    return r.exit_code == 0 && nlohmann::json::parse(r.out)["published"].get<int>() == next.load();
  }));

  server->signal(SIGTERM);
  EXPECT_EQ(server->wait(20s), 0);
  const auto after = run.status(false);
  EXPECT_EQ(after.exit_code, 1);
  EXPECT_NE(after.err.find("not running"), std::string::npos) << after.err;
}

TEST(VioServerE2E, SigtermRemovesThePipesAndTheStatusReport) {
  ServerRun run;
  auto server = run.start();
  std::string error;
  auto hub = test::MpaClient::connect(run.vio_pipe(), "voxl-vision-hub", error);
  ASSERT_TRUE(hub.connected()) << error;
  const std::string fifo = hub.fifo_path();
  EXPECT_TRUE(fs::exists(fifo));
  EXPECT_TRUE(eventually([&] { return fs::exists(run.status_file()); }));
  server->signal(SIGTERM);
  EXPECT_EQ(server->wait(20s), 0) << server->err();
  EXPECT_NE(server->err().find("removing the pipes"), std::string::npos) << server->err();
  EXPECT_FALSE(fs::exists(run.vio_pipe()));
  EXPECT_FALSE(fs::exists(run.extended_pipe()));
  EXPECT_FALSE(fs::exists(run.status_file()));
  VioData v;
  EXPECT_FALSE(hub.read_exact(&v, sizeof v, 2s)) << "the client sees the end of the pipe";
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

TEST(VioServerE2E, BadInputIsAClearErrorAndANonZeroExit) {
  ServerRun run;
  {
    std::ofstream(run.config_path()) << R"({"receiver_ip": "127.0.0.1", "receiver_port": "fourteen"})";
    Process p(run.args());
    EXPECT_EQ(p.wait(20s), 2);
    EXPECT_NE(p.err().find(run.config_path() + ": \"receiver_port\" must be an integer"), std::string::npos) << p.err();
  }
  {
    // The port is taken.
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    socklen_t len = sizeof addr;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
    std::ofstream(run.config_path()) << R"({"receiver_ip": "127.0.0.1", "receiver_port": )" << ntohs(addr.sin_port) << "}";
    Process p(run.args());
    EXPECT_EQ(p.wait(20s), 1);
    EXPECT_NE(p.err().find("is already in use"), std::string::npos) << p.err();
    EXPECT_FALSE(fs::exists(run.vio_pipe()));
    ::close(fd);
  }
  {
    Process p({HITL_VIO_SERVER_BINARY, "--config", "/proc/hitl-no-such/voxl-hitl-vio-server.conf"});
    EXPECT_EQ(p.wait(20s), 2);
    EXPECT_NE(p.err().find("cannot create /proc/hitl-no-such"), std::string::npos) << p.err();
  }
  {  // an endless file: a named error with the limit, not a hang (issue 19)
    Process p({HITL_VIO_SERVER_BINARY, "-c", "/dev/zero"});
    EXPECT_EQ(p.wait(20s), 2);
    EXPECT_NE(p.err().find("'/dev/zero' is larger than 1 MiB"), std::string::npos) << p.err();
  }
  {
    Process p({HITL_VIO_SERVER_BINARY, "--frobnicate"});
    EXPECT_EQ(p.wait(20s), 2);
    EXPECT_NE(p.err().find("unknown option --frobnicate"), std::string::npos) << p.err();
  }
  {
    Process p({HITL_VIO_SERVER_BINARY, "--json"});
    EXPECT_EQ(p.wait(20s), 2);
  }
  {
    Process p({HITL_VIO_SERVER_BINARY, "--mpa-dir", "relative/dir"});
    EXPECT_EQ(p.wait(20s), 2);
    EXPECT_NE(p.err().find("absolute path"), std::string::npos) << p.err();
  }
  {
    Process p({HITL_VIO_SERVER_BINARY, "--help"});
    EXPECT_EQ(p.wait(20s), 0);
    EXPECT_NE(p.out().find("hitl_vio_extended"), std::string::npos);
  }
}

}  // namespace
}  // namespace hitl::vio
