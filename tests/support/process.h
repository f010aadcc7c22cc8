// Runs the real hitl binary (or any program) for end-to-end tests: captures stdout and
// stderr, waits with a timeout, sends signals. Never hangs a test: the child is killed on timeout.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace hitl::test {

class Process {
 public:
  explicit Process(std::vector<std::string> argv);
  ~Process();
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  /// Waits for exit up to `timeout`; kills it (SIGKILL) after that. Returns the exit code,
  /// 128 + signal when killed by one, or -1 when it had to be killed on timeout.
  int wait(std::chrono::milliseconds timeout);
  void signal(int sig);
  bool running();
  int pid() const { return static_cast<int>(pid_); }

  /// Waits until stderr (or stdout) contains `text`; false on timeout or exit.
  bool wait_for_stderr(const std::string& text, std::chrono::milliseconds timeout);
  bool wait_for_stdout(const std::string& text, std::chrono::milliseconds timeout);

  std::string out();
  std::string err();
  /// stdout split into lines.
  std::vector<std::string> out_lines();

 private:
  void reader(int fd, std::string* sink);
  bool wait_for(const std::string* sink, const std::string& text, std::chrono::milliseconds timeout);

  pid_t pid_ = -1;
  int status_ = 0;
  bool exited_ = false;
  std::mutex mutex_;
  std::string out_;
  std::string err_;
  std::thread out_thread_;
  std::thread err_thread_;
};

/// Runs hitl with `args` to completion (timeout 60 s) and returns {exit code, stdout, stderr}.
struct RunResult {
  int exit_code;
  std::string out;
  std::string err;
};
RunResult run_hitl(const std::vector<std::string>& args, std::chrono::milliseconds timeout = std::chrono::seconds(60));

/// True while `pid` is a process that has not ended (a zombie, ended but not yet reaped, counts as ended).
bool process_running(int pid);

/// The hitl binary under test.
std::string hitl_binary();

/// A UDP port that was free a moment ago on 127.0.0.1 (ephemeral range).
uint16_t free_udp_port();

/// A fresh temporary directory, removed by the OS eventually (under the build's tmp).
std::string temp_dir();

}  // namespace hitl::test
