#include "tui/command_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstring>

#include "base/common/clock.h"

namespace hitl::tui {

Expected<std::string> own_executable() {
  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return Error{std::string("cannot find this program's path (/proc/self/exe): ") + std::strerror(errno)};
  return std::string(path, static_cast<std::size_t>(n));
}

CommandRunner::~CommandRunner() {
  if (running_.load()) {
    stop();
    const double deadline = monotonic_s() + 3.0;
    while (running_.load() && monotonic_s() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (running_.load() && pid_.load() > 0) ::kill(pid_.load(), SIGKILL);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (thread_.joinable()) thread_.join();
}

Status CommandRunner::start(const std::vector<std::string>& argv, LineSink stderr_line, DoneSink done) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (running_.load()) return Error{"a command is still running"};
  if (argv.empty()) return Error{"nothing to run"};
  if (thread_.joinable()) thread_.join();
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) return Error{std::string("pipe: ") + std::strerror(errno)};
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    return Error{std::string("pipe: ") + std::strerror(errno)};
  }
  // Everything the child needs is prepared before fork: after it, only async-signal-safe calls.
  std::vector<std::string> args = argv;
  std::vector<char*> c_args;
  for (auto& a : args) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int fd : {out_pipe[0], out_pipe[1], err_pipe[0], err_pipe[1]}) ::close(fd);
    return Error{std::string("fork: ") + std::strerror(errno)};
  }
  if (pid == 0) {
    ::setpgid(0, 0);
    const int devnull = ::open("/dev/null", O_RDONLY);
    if (devnull >= 0) ::dup2(devnull, STDIN_FILENO);
    ::dup2(out_pipe[1], STDOUT_FILENO);
    ::dup2(err_pipe[1], STDERR_FILENO);
    ::execv(c_args[0], c_args.data());
    const char msg[] = "exec failed\n";
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    ::_exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  pid_.store(pid);
  running_.store(true);
  thread_ = std::thread(&CommandRunner::supervise, this, out_pipe[0], err_pipe[0], std::move(stderr_line), std::move(done));
  return Ok{};
}

void CommandRunner::supervise(int out_fd, int err_fd, LineSink stderr_line, DoneSink done) {
  std::string out, err_partial;
  pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
  int open_fds = 2;
  char buf[4096];
  while (open_fds > 0) {
    if (::poll(fds, 2, 200) < 0 && errno != EINTR) break;
    for (auto& p : fds) {
      if (p.fd < 0 || (p.revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
      const ssize_t n = ::read(p.fd, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        ::close(p.fd);
        p.fd = -1;
        --open_fds;
        continue;
      }
      if (p.fd == out_fd) {
        if (out.size() < 1 << 20) out.append(buf, static_cast<std::size_t>(n));
        continue;
      }
      err_partial.append(buf, static_cast<std::size_t>(n));
      for (std::size_t nl; (nl = err_partial.find('\n')) != std::string::npos;) {
        if (stderr_line) stderr_line(err_partial.substr(0, nl));
        err_partial.erase(0, nl + 1);
      }
    }
  }
  if (!err_partial.empty() && stderr_line) stderr_line(err_partial);
  int status = 0;
  while (::waitpid(pid_.load(), &status, 0) < 0 && errno == EINTR) {
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : (WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1);
  pid_.store(-1);
  if (done) done(code, out);
  running_.store(false);
}

void CommandRunner::stop() {
  const pid_t pid = pid_.load();
  if (pid > 0) ::kill(pid, SIGINT);
}

}  // namespace hitl::tui
