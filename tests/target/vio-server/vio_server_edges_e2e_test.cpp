// The real voxl-hitl-vio-server at its edges: malformed packets counted and logged and the status
// report's rate and counts, SIGTERM removing the pipes and the status report, bad input a clear
// error and a non-zero exit.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/mavlink_peer.h"
#include "tests/target/vio-server/vio_server_run.h"
#include "tests/support/loopback.h"

namespace hitl::vio {
namespace {

using namespace e2e_test;

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
    sockaddr_in addr = test::loopback_address(0);
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
