// hitl-adb-relay: the board side of hitl's adb tunnel (relay.h, docs/adb.md).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "target/adb-relay/relay.h"
#include "target/adb-relay/relay_options.h"

#ifndef HITL_VERSION
#define HITL_VERSION "unknown"
#endif

namespace {

std::atomic<bool> g_stop{false};  // the one thing a signal handler may touch

void on_signal(int) { g_stop.store(true); }

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: poll() returns at once
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);
}

/// Log lines on stderr; with a time stamp when stderr is a log file.
void log_line(bool stamped, const std::string& line) {
  std::string out;
  if (stamped) {
    char stamp[32];
    const time_t now = time(nullptr);
    tm local{};
    localtime_r(&now, &local);
    strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M:%S ", &local);
    out = stamp;
  }
  out += "hitl-adb-relay: " + line + "\n";
  (void)!write(STDERR_FILENO, out.data(), out.size());
}

bool redirect_stderr_to(const std::string& path, std::string* error) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    *error = "--log: cannot open '" + path + "': " + std::strerror(errno);
    return false;
  }
  dup2(fd, STDERR_FILENO);
  close(fd);
  return true;
}

int serve(const hitl::adb::RelayOptions& o, bool stamped, int ready_fd) {
  std::string error;
  auto relay = hitl::adb::Relay::open(o.relay, [stamped](const std::string& line) { log_line(stamped, line); }, &error);
  std::string status = relay ? "ok " + relay->listen_address() + " " + std::to_string(getpid()) : "error " + error;
  if (ready_fd >= 0) {
    (void)!write(ready_fd, status.data(), status.size());
    close(ready_fd);
  }
  if (!relay) {
    log_line(stamped, "error: " + error);
    return 1;
  }
  relay->run(g_stop);
  return 0;
}

/// --daemon: the child listens and serves in its own session; the parent waits until the child is
/// listening (or has failed), says so on stdout, and exits, which ends the `adb shell` that started it.
int daemonize(const hitl::adb::RelayOptions& o) {
  int ready[2];
  if (pipe2(ready, O_CLOEXEC) != 0) {
    std::fprintf(stderr, "hitl-adb-relay: error: pipe: %s\n", std::strerror(errno));
    return 1;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    std::fprintf(stderr, "hitl-adb-relay: error: fork: %s\n", std::strerror(errno));
    return 1;
  }
  if (pid == 0) {
    close(ready[0]);
    setsid();
    if (chdir("/") != 0) { /* stays where it was; nothing depends on it */ }
    const int null_fd = open("/dev/null", O_RDWR | O_CLOEXEC);
    if (null_fd >= 0) {
      dup2(null_fd, STDIN_FILENO);
      dup2(null_fd, STDOUT_FILENO);
    }
    std::string error;
    if (!redirect_stderr_to(o.log_path, &error)) {
      const std::string status = "error " + error;
      (void)!write(ready[1], status.data(), status.size());
      _exit(1);
    }
    if (null_fd >= 0) close(null_fd);
    _exit(serve(o, true, ready[1]));
  }
  close(ready[1]);
  std::string status;
  char buf[512];
  for (;;) {
    const ssize_t n = read(ready[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    status.append(buf, static_cast<std::size_t>(n));
  }
  close(ready[0]);
  if (status.rfind("ok ", 0) == 0) {
    const auto space = status.find(' ', 3);
    std::printf("hitl-adb-relay: listening on TCP %s (pid %s, tunnel protocol %u, log %s)\n",
                status.substr(3, space - 3).c_str(), status.substr(space + 1).c_str(),
                static_cast<unsigned>(hitl::adb::kProtocolVersion), o.log_path.c_str());
    return 0;
  }
  std::fprintf(stderr, "hitl-adb-relay: error: %s\n",
               status.rfind("error ", 0) == 0 ? status.substr(6).c_str() : "the relay exited before listening");
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  const auto parsed = hitl::adb::parse_relay_options(args);
  if (!parsed.error.empty()) {
    std::fprintf(stderr, "hitl-adb-relay: %s\n", parsed.error.c_str());
    return 2;
  }
  const auto& o = parsed.options;
  if (o.help) {
    std::fputs(hitl::adb::relay_usage().c_str(), stdout);
    return 0;
  }
  if (o.version) {
    std::printf("hitl-adb-relay %s (tunnel protocol %u)\n", HITL_VERSION, static_cast<unsigned>(hitl::adb::kProtocolVersion));
    return 0;
  }
  install_signal_handlers();
  if (o.daemon) return daemonize(o);
  if (!o.log_path.empty()) {
    std::string error;
    if (!redirect_stderr_to(o.log_path, &error)) {
      std::fprintf(stderr, "hitl-adb-relay: %s\n", error.c_str());
      return 2;
    }
  }
  return serve(o, !o.log_path.empty(), -1);
}
