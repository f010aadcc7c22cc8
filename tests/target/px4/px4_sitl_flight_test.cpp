// Real PX4 in the loop (needs a PX4 SITL build made with target/px4, see docs/px4-module.md; skipped,
// saying so, without one): run-hitl-sitl.sh starts PX4 the way the VOXL2 runs it (HIL_SENSOR into
// the primary MAVLink instance, the receiver patch splitting it, dsp_hitl republishing), `hitl sim`
// flies the x500 against it, and the operator commands go through the session: `hitl shell -c
// "dsp_hitl status"` shows the counters increasing, `hitl arm`, `hitl fly takeoff --alt 5`, a 10 s
// hold (truth: the simulator's ODOMETRY), `hitl fly land` until PX4 disarms itself.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <optional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "base/mavlink/messages.h"
#include "tests/support/json_lines.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl::test {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

/// The simulator's ground truth (its ODOMETRY stream), height above the rest pose.
class Truth {
 public:
  explicit Truth(uint16_t port) : peer_(port, 0), reader_([this] { run(); }) {}
  ~Truth() {
    stop_ = true;
    reader_.join();
  }
  /// Heights (m above the first sample) seen in [from, to) of steady time.
  std::vector<double> heights_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<double> out;
    for (const auto& [t, h] : samples_) {
      if (t >= from && t < to) out.push_back(h);
    }
    return out;
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_.size();
  }

 private:
  void run() {
    while (!stop_) {
      for (const mavlink::Frame& f : peer_.receive_for(50ms)) {
        if (!f.is<mavlink::msg::Odometry>()) continue;
        const double down_m = f.as<mavlink::msg::Odometry>().z;
        std::lock_guard<std::mutex> lock(mutex_);
        if (!rest_down_m_) rest_down_m_ = down_m;
        samples_.emplace_back(std::chrono::steady_clock::now(), *rest_down_m_ - down_m);
      }
    }
  }
  MavlinkPeer peer_;
  std::mutex mutex_;
  std::optional<double> rest_down_m_;
  std::vector<std::pair<std::chrono::steady_clock::time_point, double>> samples_;
  std::atomic<bool> stop_{false};
  std::thread reader_;
};

struct DspHitlCounts {
  uint64_t imu_received = 0, imu_published = 0, mag_baro_received = 0, mag_published = 0, baro_published = 0;
  bool running = false;
};

std::optional<DspHitlCounts> parse_status(const std::string& text) {
  auto number = [&](const char* label) -> std::optional<uint64_t> {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex(std::string(label) + ": ([0-9]+)"))) return std::nullopt;
    return std::stoull(m[1]);
  };
  DspHitlCounts c;
  c.running = text.find("Running: yes") != std::string::npos;
  const auto a = number("HIL sensor_imu received"), b = number("IMU updates published"),
             d = number("HIL sensor_mag_baro received"), e = number("MAG updates published"), f = number("BARO updates published");
  if (!a || !b || !d || !e || !f) return std::nullopt;
  c.imu_received = *a;
  c.imu_published = *b;
  c.mag_baro_received = *d;
  c.mag_published = *e;
  c.baro_published = *f;
  return c;
}

class Px4Sitl : public ::testing::Test {
 protected:
  void SetUp() override {
    build_ = HITL_PX4_SITL_BUILD_DIR;
    if (build_.empty()) GTEST_SKIP() << "no PX4 SITL build: configure with -DPX4_DIR=... and build px4_hitl (docs/px4-module.md)";
    if (!fs::exists(fs::path(build_) / "bin" / "px4-dsp_hitl")) {
      GTEST_SKIP() << build_ << " has no dsp_hitl: build it with target/px4 (cmake --build <build> --target px4_hitl)";
    }
  }

  RunResult hitl(std::vector<std::string> args, std::chrono::milliseconds timeout = 120s) {
    args.insert(args.end(), {"--session-port", std::to_string(clients_port_)});
    return run_hitl(args, timeout);
  }

  std::optional<DspHitlCounts> dsp_hitl_status(std::string* text) {
    const RunResult r = hitl({"shell", "-c", "dsp_hitl status"}, 60s);
    *text = r.out;
    return r.exit_code == 0 ? parse_status(r.out) : std::nullopt;
  }

  std::string build_;
  uint16_t clients_port_ = free_udp_port();
};

TEST_F(Px4Sitl, FliesWithTheSplitAndDspHitlInTheLoop) {
  const uint16_t hil_port = free_udp_port(), sim_port = free_udp_port(), truth_port = free_udp_port();
  Truth truth(truth_port);
  Process px4({fs::path(HITL_SOURCE_DIR).append("target/px4/sitl/run-hitl-sitl.sh").string(), "--px4-build", build_, "--daemon",
               "--instance", "7", "--hil-port", std::to_string(hil_port), "--hil-remote-port", std::to_string(sim_port),
               "--onboard-port", std::to_string(free_udp_port()), "--onboard-remote-port", std::to_string(free_udp_port()),
               "--gcs-port", std::to_string(free_udp_port()), "--gcs-remote-port", std::to_string(free_udp_port())});
  ASSERT_TRUE(px4.wait_for_stdout("HITL SITL started", 120s)) << px4.out() << px4.err();

  Process sim({hitl_binary(), "--json", "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil_port), "--local-port",
               std::to_string(sim_port), "--clients", std::to_string(clients_port_), "--vio-ip", "127.0.0.1", "--vio-port",
               std::to_string(truth_port), "--seed", "3"});

  // The split and dsp_hitl: counters increasing, mag/baro at 0.4 of the IMU (100 Hz against 250 Hz).
  std::string text;
  std::optional<DspHitlCounts> first;
  for (int i = 0; i < 30 && !(first && first->imu_received > 0); ++i) {
    first = dsp_hitl_status(&text);
    if (!(first && first->imu_received > 0)) std::this_thread::sleep_for(1s);
  }
  ASSERT_TRUE(first && first->imu_received > 0) << "dsp_hitl status:\n" << text << "\nPX4:\n" << px4.out();
  std::this_thread::sleep_for(3s);
  const auto second = dsp_hitl_status(&text);
  ASSERT_TRUE(second) << text;
  std::cout << "dsp_hitl status:\n" << text << std::endl;
  EXPECT_TRUE(second->running);
  EXPECT_GT(second->imu_received, first->imu_received);
  EXPECT_GT(second->imu_published, first->imu_published);
  EXPECT_GT(second->mag_published, first->mag_published);
  EXPECT_GT(second->baro_published, first->baro_published);
  EXPECT_LE(second->imu_published, second->imu_received);
  const double mag_baro_per_imu = static_cast<double>(second->mag_baro_received - first->mag_baro_received) /
                                  static_cast<double>(second->imu_received - first->imu_received);
  EXPECT_NEAR(mag_baro_per_imu, 0.4, 0.1);

  // Arm once PX4's preflight checks pass (the estimator needs a few seconds of GPS).
  RunResult arm{1, "", ""};
  for (int i = 0; i < 45 && arm.exit_code != 0; ++i) {
    arm = hitl({"arm"}, 30s);
    if (arm.exit_code != 0) std::this_thread::sleep_for(2s);
  }
  ASSERT_EQ(arm.exit_code, 0) << arm.out << arm.err;

  const RunResult takeoff = hitl({"fly", "takeoff", "--alt", "5", "--wait", "90"}, 120s);
  ASSERT_EQ(takeoff.exit_code, 0) << takeoff.out << takeoff.err;

  const auto hold_from = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(10s);
  const std::vector<double> hold = truth.heights_between(hold_from, std::chrono::steady_clock::now());
  ASSERT_GT(hold.size(), 100U) << "no ODOMETRY truth during the hold";
  double mean = 0, max_dev = 0;
  for (double h : hold) mean += h;
  mean /= static_cast<double>(hold.size());
  double var = 0;
  for (double h : hold) {
    var += (h - mean) * (h - mean);
    max_dev = std::max(max_dev, std::fabs(h - 5.0));
  }
  const double std_m = std::sqrt(var / static_cast<double>(hold.size()));
  std::cout << "hold 10 s: mean " << mean << " m, std " << std_m << " m, max |h - 5| " << max_dev << " m (" << hold.size()
            << " samples)" << std::endl;
  RecordProperty("hold_mean_m", std::to_string(mean));
  RecordProperty("hold_std_m", std::to_string(std_m));
  EXPECT_NEAR(mean, 5.0, 0.7);
  EXPECT_LT(max_dev, 1.5);

  const RunResult land = hitl({"fly", "land", "--wait", "120"}, 150s);
  EXPECT_EQ(land.exit_code, 0) << land.out << land.err;

  const auto after = dsp_hitl_status(&text);
  ASSERT_TRUE(after) << text;
  EXPECT_GT(after->imu_received, second->imu_received);

  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(20s), 0) << sim.err();
  // The landing check (issue 20): one touchdown, no rebound over 5 cm, no IMU sample clipped.
  const auto summary = last_json_line(sim.out());
  std::cout << "landing: " << summary["landing"].dump() << ", IMU clipped: " << summary["imu_saturated"].dump() << std::endl;
  EXPECT_EQ(summary["landing"]["touchdowns"], 1) << summary["landing"].dump();
  EXPECT_LE(summary["landing"]["max_rebound_m"].get<double>(), 0.05) << summary["landing"].dump();
  EXPECT_EQ(summary["imu_saturated"]["accel"], 0);
  px4.signal(SIGTERM);
  px4.wait(30s);
}

}  // namespace
}  // namespace hitl::test
