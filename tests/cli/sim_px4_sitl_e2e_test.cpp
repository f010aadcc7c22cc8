// hitl sim end to end, --px4-sitl: the bare flag serves TCP 4560; a peer that connects as PX4 SITL's
// simulator_mavlink does is served in lockstep on the simulator's clock, and one still on an
// earlier session's clock is told what to restart.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <memory>

#include "base/mavlink/frame_encoder.h"
#include "tests/cli/sim_board.h"
#include "tests/support/loopback.h"

namespace hitl {
namespace {

using namespace sim_e2e;

TEST(SimE2E, BarePx4SitlFlagServesTcp4560) {
  // The documented form, with no value: it must mean tcp:4560, not fall back to a board link.
  Process sim({test::hitl_binary(), "sim", "--px4-sitl", "--no-vio", "--clients", "0", "--bind", "127.0.0.1",
               "--duration", "0.1"});
  const bool serving = sim.wait_for_stderr("waiting for PX4 SITL to connect to TCP 127.0.0.1:4560", 10s) ||
                       sim.err().find("4560") != std::string::npos;  // or 4560 was taken: the error names it
  EXPECT_TRUE(serving) << sim.err();
  EXPECT_EQ(sim.err().find("HIL_SENSOR/HIL_GPS to"), std::string::npos) << sim.err();
  sim.signal(SIGINT);
  sim.wait(10s);
}

TEST(SimE2E, Px4SitlWarnsThatAModeConditionCanNeverHoldAndTheSummaryListsIt) {
  // PX4 SITL's simulator link carries PX4's HEARTBEAT once, at connect: a mode condition never holds.
  const std::string scenario = test::temp_dir() + "/mode.json";
  {
    std::FILE* f = std::fopen(scenario.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(R"({"events": [{"id": "on-hold", "when": {"mode": "Hold"}, "fault": "gps-loss"}]})", f);
    std::fclose(f);
  }
  const uint16_t port = test::free_udp_port();
  Process sim({test::hitl_binary(), "sim", "--px4-sitl", "tcp:" + std::to_string(port), "--no-vio", "--clients", "0",
               "--bind", "127.0.0.1", "--scenario", scenario});
  EXPECT_TRUE(sim.wait_for_stderr("fault on-hold: its 'mode' condition can never hold", 10s)) << sim.err();
  sim.signal(SIGINT);
  sim.wait(10s);
  EXPECT_NE(sim.out().find("fault on-hold (gps-loss): never started"), std::string::npos) << sim.out();
}

/// `hitl sim --px4-sitl tcp:PORT`, unpaced, waiting for PX4 to connect.
std::unique_ptr<Process> start_px4_sitl_session(uint16_t port) {
  auto sim = std::make_unique<Process>(std::vector<std::string>{
      test::hitl_binary(), "--json", "sim", "--px4-sitl", "tcp:" + std::to_string(port), "--no-vio", "--clients", "0",
      "--speed", "0", "--bind", "127.0.0.1"});
  EXPECT_TRUE(sim->wait_for_stderr("waiting for PX4 SITL", 10s)) << sim->err();
  return sim;
}

/// Connects to the session as PX4 SITL's simulator_mavlink does; -1 when it cannot.
int connect_as_px4_sitl(uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr = test::loopback_address(port);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) return fd;
  ::close(fd);
  return -1;
}

/// Plays PX4 SITL's simulator_mavlink: connects to hitl over TCP, answers in lockstep.
TEST(SimE2E, Px4SitlOverTcpLockstepOnTheSimulatorsClock) {
  const uint16_t port = test::free_udp_port();  // a free number; TCP on the same number is very likely free too
  auto session = start_px4_sitl_session(port);
  Process& sim = *session;
  const int fd = connect_as_px4_sitl(port);
  ASSERT_GE(fd, 0);
  auto set = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(set);
  mavlink::FrameEncoder px4(1, 1);
  uint64_t sensors = 0, last_t = 0;
  bool monotonic = true;
  uint8_t buf[4096];
  while (sensors < 1000) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    ASSERT_GT(n, 0);
    parser.feed({buf, static_cast<std::size_t>(n)}, [&](const mavlink::Frame& f) {
      if (!f.is<msg::HilSensor>()) return;
      const auto s = f.as<msg::HilSensor>();
      monotonic &= s.time_usec > last_t;
      last_t = s.time_usec;
      ++sensors;
      if (sensors < 275) return;  // PX4 boots ~1.1 s of simulated time before it answers
      mavlink::FrameBuffer out;
      const std::size_t len = px4.encode(actuators(0.0, false), out);
      ASSERT_EQ(::send(fd, out.data(), len, MSG_NOSIGNAL), static_cast<ssize_t>(len));
    });
  }
  EXPECT_TRUE(monotonic);
  EXPECT_EQ(last_t, sensors * 4000);
  ::close(fd);  // PX4 exits: the session must end, saying why
  EXPECT_EQ(sim.wait(30s), 1);
  EXPECT_NE(sim.err().find("PX4 SITL disconnected"), std::string::npos) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["end"], "flight_stack_gone");
  // Answers to the HIL_SENSORs sent unpaced before PX4's first answer arrive together and one wait
  // takes them all, so the count of waits is below the 725 answers by a load-dependent amount.
  EXPECT_GE(j["lockstep"]["waits"].get<int>(), 200);
  EXPECT_EQ(j["lockstep"]["fallbacks"], 0);
}

/// PX4 SITL still on an earlier session's clock: its answers are stamped far ahead; the session
/// says so once, and what to restart.
TEST(SimE2E, Px4SitlOnAnEarlierSessionsClockIsSaid) {
  const uint16_t port = test::free_udp_port();
  auto session = start_px4_sitl_session(port);
  Process& sim = *session;
  const int fd = connect_as_px4_sitl(port);
  ASSERT_GE(fd, 0);
  auto set = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(set);
  mavlink::FrameEncoder px4(1, 1);
  uint64_t sensors = 0;
  uint8_t buf[4096];
  while (sensors < 300) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    ASSERT_GT(n, 0);
    parser.feed({buf, static_cast<std::size_t>(n)}, [&](const mavlink::Frame& f) {
      if (!f.is<msg::HilSensor>()) return;
      ++sensors;
      auto a = actuators(0.0, false);
      a.time_usec = f.as<msg::HilSensor>().time_usec + 600000000;  // 10 minutes into an earlier session
      mavlink::FrameBuffer out;
      const std::size_t len = px4.encode(a, out);
      ASSERT_EQ(::send(fd, out.data(), len, MSG_NOSIGNAL), static_cast<ssize_t>(len));
    });
  }
  ::close(fd);
  EXPECT_EQ(sim.wait(30s), 1);
  EXPECT_NE(sim.err().find("still runs on an earlier session's time"), std::string::npos) << sim.err();
  EXPECT_NE(sim.err().find("Restart PX4 SITL together with hitl sim"), std::string::npos) << sim.err();
}

}  // namespace
}  // namespace hitl
