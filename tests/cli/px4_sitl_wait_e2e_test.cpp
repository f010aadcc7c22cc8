// `hitl sim --px4-sitl` waiting for PX4 says what to start (the PX4 command), not only where it waits.
#include <gtest/gtest.h>

#include <csignal>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(Px4SitlWaitE2E, SaysThePx4CommandToRun) {
  test::Process sim({test::hitl_binary(), "sim", "--px4-sitl", "tcp:" + std::to_string(test::free_udp_port()), "--no-vio",
                     "--clients", "0"});
  EXPECT_TRUE(sim.wait_for_stderr("PX4_SYS_AUTOSTART=10016 PX4_SIM_MODEL=none_iris build/px4_sitl_default/bin/px4", 20s))
      << sim.err();
  sim.signal(SIGINT);
  EXPECT_EQ(sim.wait(20s), 0) << sim.err();
}

}  // namespace
}  // namespace hitl
