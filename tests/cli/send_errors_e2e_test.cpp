// Sends the kernel refuses are never counted as sent (issue 18): `hitl sim` to an address it cannot
// reach says so at once with the errno and the fix, counts them in `send_errors`, and exits 1 when
// its --duration ends with nothing delivered. Without a real network: bound to 127.0.0.1 (--bind),
// the simulator cannot reach 192.0.2.1 (TEST-NET-1), and the kernel refuses every send at once; the
// other commands bind 0.0.0.0, so they are sent to 255.255.255.255, which the kernel refuses
// (EACCES: no SO_BROADCAST) without a datagram leaving the machine.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(SendErrorsE2E, SimToAnUnreachableAddressSaysSoAndFails) {
  test::Process sim({test::hitl_binary(), "--json", "sim", "--bind", "127.0.0.1", "-i", "192.0.2.1", "--local-port",
                     std::to_string(test::free_udp_port()), "--clients", "0", "--duration", "3", "--speed", "1"});
  // Said at once (the first step sends), not after the 2-s no-answer warning.
  ASSERT_TRUE(sim.wait_for_stderr("cannot send to 192.0.2.1:14560", 10s)) << sim.err();
  const int code = sim.wait(60s);
  const std::string err = sim.err();
  EXPECT_EQ(code, 1) << err;
  EXPECT_NE(err.find("(EINVAL)"), std::string::npos) << err;
  EXPECT_NE(err.find("bound to 127.0.0.1 (--bind)"), std::string::npos) << err;
  EXPECT_NE(err.find("cannot send to 192.0.2.1:14570"), std::string::npos) << err;  // the VIO link's own destination
  EXPECT_NE(err.find("every send failed"), std::string::npos) << err;               // the no-answer warning says why
  EXPECT_NE(err.find("nothing was delivered"), std::string::npos) << err;
  const auto j = test::last_json_line(sim.out());
  EXPECT_EQ(j["type"], "summary");
  EXPECT_GT(j["send_errors"].get<uint64_t>(), 500u);
  EXPECT_NE(j["send_error"].get<std::string>().find("EINVAL"), std::string::npos);
  for (const auto& [name, stream] : j["sent"].items()) EXPECT_EQ(stream["count"], 0) << name;
  // The status objects count them as they happen.
  bool status_counted = false;
  for (const auto& line : sim.out_lines()) {
    const auto s = nlohmann::json::parse(line, nullptr, false);
    if (s.is_object() && s.value("type", "") == "status" && s.value("send_errors", 0) > 0) status_counted = true;
  }
  EXPECT_TRUE(status_counted) << sim.out();
}

TEST(SendErrorsE2E, BoardCommandsSayTheSendErrorInsteadOfWaiting) {
  const auto r = test::run_hitl({"arm", "-i", "255.255.255.255", "--local-port", std::to_string(test::free_udp_port())}, 30s);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot send to 255.255.255.255:14558"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(EACCES)"), std::string::npos) << r.err;
}

TEST(SendErrorsE2E, InspectConnectCountsAndFails) {
  const auto r = test::run_hitl({"--json", "inspect", "--connect", "255.255.255.255:14558", "--duration", "2"}, 30s);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot send to 255.255.255.255:14558"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("every HEARTBEAT failed to send"), std::string::npos) << r.err;
  EXPECT_GE(test::last_json_line(r.out)["send_errors"].get<uint64_t>(), 1u) << r.out;
}

TEST(SendErrorsE2E, BridgeNeverCountsARefusedPacketAsSent) {
  test::Process bridge({test::hitl_binary(), "--json", "bridge", "-i", "255.255.255.255", "--local-port",
                        std::to_string(test::free_udp_port()), "--clients", "0", "--duration", "2"});
  bridge.wait(30s);
  const std::string err = bridge.err();
  EXPECT_NE(err.find("cannot send to 255.255.255.255:14558"), std::string::npos) << err;
  bool counted = false;
  for (const auto& line : bridge.out_lines()) {
    const auto j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_object() || !j.contains("links")) continue;
    const auto& board = j["links"][0];
    EXPECT_EQ(board["packets_out"], 0) << line;
    if (board["send_errors"].get<uint64_t>() > 0) counted = true;
  }
  EXPECT_TRUE(counted) << bridge.out();
}

}  // namespace
}  // namespace hitl
