// One exit-code table for every command (cli/common_options.h, README, man page EXIT STATUS):
// 0 success; 1 a check failed, the board refused or did not answer; 2 bad usage or input, a port
// in use. Each command is held to it here.
#include <gtest/gtest.h>

#include "engine/net/udp_endpoint.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

TEST(ExitCodes, APortInUseIsTwoInEveryCommand) {
  net::UdpEndpoint::Config c;
  c.bind_address = "0.0.0.0";
  auto held = net::UdpEndpoint::open(c);
  ASSERT_TRUE(held) << held.error().message;
  const std::string busy = std::to_string(held->local_address().port());
  const std::string free = std::to_string(test::free_udp_port());
  const std::vector<std::vector<std::string>> commands = {
      {"sim", "--local-port", busy, "--no-vio", "--clients", "0", "--duration", "1"},
      {"inspect", "--port", busy, "--duration", "1"},
      {"target", "--hil-port", busy, "--gcs-port", free, "--vio-port", "0", "--duration", "1"},
      {"bridge", "-i", "127.0.0.1", "--local-port", busy, "--clients", "0", "--duration", "1"},
  };
  for (const auto& args : commands) {
    const auto r = test::run_hitl(args, 30s);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("in use"), std::string::npos) << args[0] << ": " << r.err;
  }
}

TEST(ExitCodes, ABoardAddressThatDoesNotResolveIsTwoAndNamesTheOption) {
  const std::string free = std::to_string(test::free_udp_port());
  const std::vector<std::vector<std::string>> commands = {
      {"sim", "--local-port", free, "--no-vio", "--clients", "0", "--duration", "1"},
      {"arm", "--local-port", free},
      {"bridge", "--local-port", free, "--clients", "0", "--duration", "1"},
  };
  for (auto args : commands) {
    args.insert(args.end(), {"-i", "no.such.host.invalid"});
    const auto r = test::run_hitl(args, 30s);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("-i (the board's address"), std::string::npos) << args[0] << ": " << r.err;
    EXPECT_NE(r.err.find("no.such.host.invalid"), std::string::npos) << args[0] << ": " << r.err;
  }
}

TEST(ExitCodes, NoBoardIsOneInEveryBoardCommand) {
  // 255.255.255.255: the kernel refuses every send at once, so no command waits out its timeout.
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"arm"}, {"disarm"}, {"fly", "takeoff"}, {"params", "check"}, {"shell", "-c", "ver all"}}) {
    std::vector<std::string> argv = args;
    for (const char* a : {"-i", "255.255.255.255", "--local-port"}) argv.push_back(a);
    argv.push_back(std::to_string(test::free_udp_port()));
    const auto r = test::run_hitl(argv, 30s);
    EXPECT_EQ(r.exit_code, 1) << args[0] << ": " << r.err;
  }
}

TEST(ExitCodes, BadUsageIsTwo) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"sim", "--no-such-option"}, {"inspect", "--port", "70000"}, {"demo", "--speed", "-1"}, {"bridge", "--endpoint", "bogus"}}) {
    const auto r = test::run_hitl(args, 30s);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
  }
}

}  // namespace
}  // namespace hitl
