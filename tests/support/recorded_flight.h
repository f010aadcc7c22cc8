// A recording made the way the engine's figures are checked end to end: `hitl sim --lockstep
// --speed 0 ... --record TLOG` against a fresh `hitl target --lockstep` on free loopback ports
// (no VIO, no client port). The Allan, spectrum and report tests read what it records.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <string>
#include <vector>

#include "tests/support/process.h"

namespace hitl::test {

/// Records the flight `sim_args` describe (-t, --duration, --vehicle, --fault ...) to `tlog`; its
/// path, or empty with a test failure when the board did not start or the flight did not end with
/// exit 0 within `limit`.
inline std::string record_against_target(const std::string& tlog, const std::vector<std::string>& sim_args,
                                         std::chrono::seconds limit) {
  using namespace std::chrono_literals;
  const uint16_t hil = free_udp_port();
  Process board({hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
                 std::to_string(free_udp_port()), "--vio-port", "0", "--lockstep"});
  if (!board.wait_for_stderr("EMULATED", 10s)) {
    ADD_FAILURE() << board.err();
    return "";
  }
  std::vector<std::string> args{hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
                                std::to_string(free_udp_port()), "--no-vio", "--clients", "0", "--lockstep", "--speed", "0",
                                "--record", tlog};
  args.insert(args.end(), sim_args.begin(), sim_args.end());
  Process sim(args);
  const int code = sim.wait(limit);
  board.signal(SIGINT);
  board.wait(20s);
  if (code != 0) {
    ADD_FAILURE() << sim.err();
    return "";
  }
  return tlog;
}

}  // namespace hitl::test
