// Runs another hitl command beside the dashboard, exactly as an operator would from a second
// terminal (the `f` key runs `hitl fly trajectory FILE` through the session's client port): its
// stderr lines and its result reach callbacks as they come; stop() interrupts it with SIGINT.
// The child gets its own process group, so a Ctrl-C meant for the dashboard does not reach it.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "base/common/expected.h"

namespace hitl::tui {

/// This process's own executable (/proc/self/exe), to run hitl subcommands with.
Expected<std::string> own_executable();

class CommandRunner {
 public:
  using LineSink = std::function<void(const std::string& line)>;
  /// Exit code (128 + signal when killed by one) and everything it wrote to stdout.
  using DoneSink = std::function<void(int exit_code, const std::string& out)>;

  CommandRunner() = default;
  ~CommandRunner();  ///< interrupts a running command and waits for it (then kills it after 3 s)
  CommandRunner(const CommandRunner&) = delete;
  CommandRunner& operator=(const CommandRunner&) = delete;

  /// Starts `argv` (argv[0] the program); an Error when one still runs or it cannot start.
  Status start(const std::vector<std::string>& argv, LineSink stderr_line, DoneSink done);
  bool running() const { return running_.load(); }
  /// SIGINT to the command (it finishes on its own way out).
  void stop();

 private:
  void supervise(int out_fd, int err_fd, LineSink stderr_line, DoneSink done);
  std::atomic<bool> running_{false};
  std::atomic<pid_t> pid_{-1};
  std::mutex mutex_;
  std::thread thread_;
};

}  // namespace hitl::tui
