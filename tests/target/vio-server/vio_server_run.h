// What the voxl-hitl-vio-server end-to-end tests share: the real server in a temporary directory of
// its own, ODOMETRY number i with every field traceable to i and the check of the record it
// becomes, a reader of whole MPA records, and waiting for a condition.
#pragma once

#include <gtest/gtest.h>
#include <time.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "target/vio-server/vio_data.h"
#include "tests/support/process.h"
#include "tests/target/vio-server/mpa_client.h"

namespace hitl::vio::e2e_test {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using test::Process;

inline constexpr double kRate_hz = 250.0;

inline int64_t monotonic_ns() {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

/// ODOMETRY number i: every field carries something of i, so each record can be traced back.
inline mavlink::msg::Odometry odometry_number(int i) {
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
inline void expect_record_matches(const VioData& v, int i) {
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

}  // namespace hitl::vio::e2e_test
