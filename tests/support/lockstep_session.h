// `hitl target --lockstep` and `hitl sim --lockstep --speed 5` against it on free loopback ports,
// with the session's client port open: the set-up of the tests that fly `hitl fly` through a session.
#pragma once

#include <chrono>
#include <csignal>
#include <memory>
#include <string>
#include <vector>

#include "tests/support/process.h"

namespace hitl::test {

class LockstepSessionWithClients {
 public:
  LockstepSessionWithClients() {
    using namespace std::chrono_literals;
    board_ = std::make_unique<Process>(std::vector<std::string>{
        hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil_), "--gcs-port",
        std::to_string(free_udp_port()), "--vio-port", "0", "--lockstep"});
    if (!board_->wait_for_stderr("EMULATED", 10s)) {
      failure_ = "hitl target did not start: " + board_->err();
      return;
    }
    sim_ = std::make_unique<Process>(std::vector<std::string>{
        hitl_binary(), "sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil_), "--local-port",
        std::to_string(free_udp_port()), "--no-vio", "--clients", std::to_string(clients_), "--lockstep", "--speed", "5",
        "--duration", "300"});
    if (!sim_->wait_for_stderr("clients on", 10s)) failure_ = "hitl sim did not start: " + sim_->err();
  }
  ~LockstepSessionWithClients() { stop(); }
  LockstepSessionWithClients(const LockstepSessionWithClients&) = delete;
  LockstepSessionWithClients& operator=(const LockstepSessionWithClients&) = delete;

  uint16_t client_port() const { return clients_; }
  /// Empty when both run; else what did not start, with its stderr.
  const std::string& failure() const { return failure_; }

  /// `hitl --json fly` through the session's client port on free local ports, then `args`
  /// (e.g. "trajectory", FILE).
  std::vector<std::string> fly(const std::vector<std::string>& args) const {
    std::vector<std::string> argv{"--json",  "fly",  "--session-port", std::to_string(clients_),
                                  "-i",      "127.0.0.1", "--port",     std::to_string(free_udp_port()),
                                  "--local-port", std::to_string(free_udp_port())};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
  }

  /// Ctrl-C to the session, then to the board (idempotent).
  void stop() {
    using namespace std::chrono_literals;
    if (sim_) sim_->signal(SIGINT), sim_->wait(20s), sim_.reset();
    if (board_) board_->signal(SIGINT), board_->wait(20s), board_.reset();
  }

 private:
  uint16_t hil_ = free_udp_port(), clients_ = free_udp_port();
  std::unique_ptr<Process> board_, sim_;
  std::string failure_;
};

}  // namespace hitl::test
