#include "engine/net/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "base/common/clock.h"

extern char** environ;

namespace hitl::net {
namespace {

/// Reads what is waiting on a non-blocking pipe; false once it is at end of file.
bool drain(int fd, std::string* sink) {
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      sink->append(buf, static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
  }
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace

std::string command_line(const std::string& program, const std::vector<std::string>& args) {
  std::string line = program;
  for (const auto& a : args) {
    const bool quote = a.empty() || a.find_first_of(" \t'\"$&|;<>()*?") != std::string::npos;
    line += quote ? " '" + a + "'" : " " + a;
  }
  return line;
}

std::optional<std::string> find_on_path(std::string_view name) {
  if (name.empty()) return std::nullopt;
  if (name.find('/') != std::string_view::npos) {
    const std::string path(name);
    if (::access(path.c_str(), X_OK) == 0) return path;
    return std::nullopt;
  }
  const char* env = std::getenv("PATH");
  const std::string path_list = env ? env : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= path_list.size()) {
    const std::size_t end = path_list.find(':', start);
    std::string dir = path_list.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/" + std::string(name);
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return std::nullopt;
}

Expected<ProgramOutput> run_program(const std::string& program, const std::vector<std::string>& args, int timeout_ms) {
  const std::string what = "'" + command_line(program, args) + "'";
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) return Error::unavailable(what + ": cannot create a pipe: " + std::strerror(errno));
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    const std::string why = std::strerror(errno);
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    return Error::unavailable(what + ": cannot create a pipe: " + why);
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
  std::vector<std::string> argv_text{program};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (spawned != 0) {
    ::close(out_pipe[0]);
    ::close(err_pipe[0]);
    return Error::unavailable(what + ": cannot start it: " + std::strerror(spawned));
  }
  for (int fd : {out_pipe[0], err_pipe[0]}) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL, 0) | O_NONBLOCK);

  ProgramOutput result;
  bool out_open = true, err_open = true, exited = false, timed_out = false;
  int status = 0;
  const int64_t deadline_ms = monotonic_ms() + timeout_ms;
  while (!exited) {
    pollfd fds[2];
    nfds_t n = 0;
    if (out_open) fds[n++] = {out_pipe[0], POLLIN, 0};
    if (err_open) fds[n++] = {err_pipe[0], POLLIN, 0};
    // Short polls: the exit is noticed by waitpid, not by end of file (a daemon may keep the pipes).
    ::poll(fds, n, n ? 20 : 0);
    if (n == 0) ::usleep(20000);
    if (out_open) out_open = drain(out_pipe[0], &result.out);
    if (err_open) err_open = drain(err_pipe[0], &result.err);
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) exited = true;
    else if (w < 0 && errno != EINTR) break;
    if (!exited && monotonic_ms() > deadline_ms) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      timed_out = true;
      break;
    }
  }
  // What the program wrote just before it exited.
  if (out_open) drain(out_pipe[0], &result.out);
  if (err_open) drain(err_pipe[0], &result.err);
  ::close(out_pipe[0]);
  ::close(err_pipe[0]);
  if (timed_out) {
    const std::string limit = timeout_ms % 1000 == 0 ? std::to_string(timeout_ms / 1000) + " s" : std::to_string(timeout_ms) + " ms";
    return Error::failed(what + " did not finish within " + limit + " (killed)");
  }
  result.exit_code = exit_code_of(status);
  return result;
}

}  // namespace hitl::net
