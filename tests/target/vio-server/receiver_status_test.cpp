// The UDP side (what counts as malformed, what is ODOMETRY) and the status report.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "base/mavlink/frame_encoder.h"
#include "target/vio-server/odometry_receiver.h"
#include "target/vio-server/server_status.h"
#include "tests/support/mavlink_peer.h"
#include "tests/support/process.h"

namespace hitl::vio {
namespace {

using namespace std::chrono_literals;

struct Received {
  std::vector<mavlink::msg::Odometry> odometry;
  std::vector<std::string> malformed;
};

/// Drains until `n_datagrams` have been seen (loopback delivers them; the wait is generous).
Received drain_until(OdometryReceiver& rx, uint64_t n_datagrams) {
  Received r;
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (rx.counters().datagrams < n_datagrams && std::chrono::steady_clock::now() < deadline) {
    rx.drain([&](const mavlink::msg::Odometry& m) { r.odometry.push_back(m); },
             [&](const std::string& why) { r.malformed.push_back(why); });
    std::this_thread::sleep_for(2ms);
  }
  return r;
}

TEST(OdometryReceiver, HandsOnOdometryAndCountsEverythingElse) {
  auto rx = OdometryReceiver::open("127.0.0.1", 0);
  ASSERT_TRUE(rx.ok()) << rx.error().message;
  test::MavlinkPeer peer(0, rx.value()->port(), 250, 197);

  mavlink::msg::Odometry odom;
  odom.x = 7.0f;
  odom.q = {1, 0, 0, 0};
  peer.send(odom);                                      // 1: ODOMETRY
  peer.send(mavlink::msg::Heartbeat{});                 // 2: another message
  const std::vector<uint8_t> garbage{'h', 'e', 'l', 'l', 'o', 0x00, 0x42};
  peer.send_bytes(garbage);                             // 3: not MAVLink
  mavlink::FrameBuffer buf;
  std::size_t n = peer.encoder().encode(odom, buf);
  buf[n - 1] ^= 0xFF;                                   // 4: checksum broken
  peer.send_bytes({buf.data(), n});
  n = peer.encoder().encode(odom, buf);
  peer.send_bytes({buf.data(), n / 2});                 // 5: cut off
  n = peer.encoder().encode(odom, buf);
  peer.send_bytes({buf.data(), n});                     // 6: ODOMETRY again, after all that
  const Received r = drain_until(*rx.value(), 6);

  const ReceiverCounters& c = rx.value()->counters();
  EXPECT_EQ(c.datagrams, 6u);
  EXPECT_EQ(c.odometry, 2u);
  ASSERT_EQ(r.odometry.size(), 2u);
  EXPECT_EQ(r.odometry[0].x, 7.0f);
  EXPECT_EQ(c.other_messages, 1u);
  EXPECT_EQ(c.malformed_datagrams, 3u);
  EXPECT_GE(c.garbage_runs, 1u);
  EXPECT_GE(c.crc_errors, 1u);
  EXPECT_EQ(c.truncated, 1u);
  ASSERT_EQ(r.malformed.size(), 3u);
  EXPECT_NE(r.malformed[0].find("from 127.0.0.1:" + std::to_string(peer.endpoint().local_address().port())), std::string::npos)
      << r.malformed[0];
  EXPECT_NE(r.malformed[1].find("checksum"), std::string::npos) << r.malformed[1];
  EXPECT_NE(r.malformed[2].find("cut off"), std::string::npos) << r.malformed[2];
}

TEST(OdometryReceiver, APortInUseIsAClearError) {
  auto first = OdometryReceiver::open("127.0.0.1", 0);
  ASSERT_TRUE(first.ok());
  auto second = OdometryReceiver::open("127.0.0.1", first.value()->port());
  ASSERT_FALSE(second.ok());
  EXPECT_NE(second.error().message.find("already in use"), std::string::npos) << second.error().message;
  EXPECT_FALSE(OdometryReceiver::open("not-an-ip", 0).ok());
}

ServerStatus sample_status() {
  ServerStatus s;
  s.pid = static_cast<int>(::getpid());
  s.listen = "0.0.0.0:14570";
  s.pipe_implementation = "hitl's MPA implementation";
  s.uptime_s = 12.5;
  s.updated_unix_ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  s.odometry_rate_hz = 249.8;
  s.receiver.datagrams = 3000;
  s.receiver.odometry = 2990;
  s.receiver.malformed_datagrams = 4;
  s.receiver.crc_errors = 3;
  s.published = 2989;
  s.invalid_odometry = 1;
  s.pipes.push_back({"/run/mpa/hitl_vio/", "vio_data_t", 1, {2989, 0, 1, 2}});
  return s;
}

TEST(ServerStatus, RoundTripsThroughTheStatusFileAndReadsInWords) {
  const std::string path = test::temp_dir() + "/run/status.json";
  ASSERT_TRUE(write_status_file(path, sample_status()).ok());
  auto report = read_status_file(path);
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_EQ(report->status.receiver.odometry, 2990u);
  EXPECT_EQ(report->status.pipes.at(0).counters.requests_rejected, 2u);
  EXPECT_LT(report->age_s, 5.0);
  const std::string text = format_status(report.value());
  EXPECT_NE(text.find("249.8 Hz, 2990 received, 2989 published, 1 invalid"), std::string::npos) << text;
  EXPECT_NE(text.find("4 malformed (3 checksum errors"), std::string::npos) << text;
  EXPECT_NE(text.find("/run/mpa/hitl_vio/ (vio_data_t): 1 client(s)"), std::string::npos) << text;
}

TEST(ServerStatus, NoServerStaleReportOrExitedProcessIsSaidSo) {
  const std::string dir = test::temp_dir();
  auto none = read_status_file(dir + "/none.json");
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("not running"), std::string::npos);

  ServerStatus stale = sample_status();
  stale.updated_unix_ms -= 60'000;
  ASSERT_TRUE(write_status_file(dir + "/stale.json", stale).ok());
  auto old = read_status_file(dir + "/stale.json");
  ASSERT_FALSE(old.ok());
  EXPECT_NE(old.error().message.find("has not reported for 60 s"), std::string::npos) << old.error().message;

  const pid_t dead = ::fork();
  if (dead == 0) std::_Exit(0);
  ::waitpid(dead, nullptr, 0);
  ServerStatus gone = sample_status();
  gone.pid = dead;
  ASSERT_TRUE(write_status_file(dir + "/gone.json", gone).ok());
  auto exited = read_status_file(dir + "/gone.json");
  ASSERT_FALSE(exited.ok());
  EXPECT_NE(exited.error().message.find("has exited"), std::string::npos);

  std::ofstream(dir + "/junk.json") << "{\"pid\": 1}";
  auto junk = read_status_file(dir + "/junk.json");
  ASSERT_FALSE(junk.ok());
  EXPECT_NE(junk.error().message.find("not a voxl-hitl-vio-server status report"), std::string::npos);
}

}  // namespace
}  // namespace hitl::vio
