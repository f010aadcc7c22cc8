// A dashboard quitting does not wait out a discovery (issue 18: Ctrl-C with --tui took 2-6 s):
// connect_patiently's discovery ends soon after its stop flag is set, not after --timeout.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "engine/net/udp_endpoint.h"
#include "engine/vehicle/patient_link.h"
#include "tests/support/process.h"

namespace hitl::vehicle {
namespace {

TEST(PatientLink, StopEndsADiscoveryInProgress) {
  // A port where a socket listens but no autopilot ever answers: discovery would take the timeout.
  net::UdpEndpoint::Config c;
  c.bind_address = "127.0.0.1";
  auto silent = net::UdpEndpoint::open(c);
  ASSERT_TRUE(silent);
  auto options = session_client_options(silent->local_address().port(), 60.0);
  std::atomic<bool> stop{false};
  const auto start = std::chrono::steady_clock::now();
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    stop.store(true);
  });
  auto link = connect_patiently(options, stop, {});
  stopper.join();
  EXPECT_EQ(link, nullptr);
  // Far below the 60-s discovery timeout (a generous bound: the machine may be loaded).
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

}  // namespace
}  // namespace hitl::vehicle
