#include "tests/support/process.h"

#include "tests/support/loopback.h"

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace hitl::test {

Process::Process(std::vector<std::string> argv) {
  int out_pipe[2];
  int err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    ::dup2(out_pipe[1], STDOUT_FILENO);
    ::dup2(err_pipe[1], STDERR_FILENO);
    int devnull = ::open("/dev/null", O_RDONLY);
    ::dup2(devnull, STDIN_FILENO);
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    std::fprintf(stderr, "exec %s failed: %s\n", args[0], std::strerror(errno));
    std::_Exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  out_thread_ = std::thread(&Process::reader, this, out_pipe[0], &out_);
  err_thread_ = std::thread(&Process::reader, this, err_pipe[0], &err_);
}

Process::~Process() {
  if (!exited_) {
    ::kill(pid_, SIGKILL);
    wait(std::chrono::seconds(5));
  }
  if (out_thread_.joinable()) out_thread_.join();
  if (err_thread_.joinable()) err_thread_.join();
}

void Process::reader(int fd, std::string* sink) {
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    std::lock_guard<std::mutex> lock(mutex_);
    sink->append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
}

bool Process::running() {
  if (exited_) return false;
  int status = 0;
  if (::waitpid(pid_, &status, WNOHANG) == pid_) {
    exited_ = true;
    status_ = status;
    return false;
  }
  return true;
}

int Process::wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  bool killed = false;
  while (running()) {
    if (std::chrono::steady_clock::now() > deadline && !killed) {
      ::kill(pid_, SIGKILL);
      killed = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (out_thread_.joinable()) out_thread_.join();
  if (err_thread_.joinable()) err_thread_.join();
  if (killed) return -1;
  if (WIFEXITED(status_)) return WEXITSTATUS(status_);
  if (WIFSIGNALED(status_)) return 128 + WTERMSIG(status_);
  return -1;
}

void Process::signal(int sig) {
  if (!exited_) ::kill(pid_, sig);
}

bool Process::wait_for(const std::string* sink, const std::string& text, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (sink->find(text) != std::string::npos) return true;
    }
    if (!running()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      std::lock_guard<std::mutex> lock(mutex_);
      return sink->find(text) != std::string::npos;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

bool Process::wait_for_stderr(const std::string& text, std::chrono::milliseconds timeout) { return wait_for(&err_, text, timeout); }
bool Process::wait_for_stdout(const std::string& text, std::chrono::milliseconds timeout) { return wait_for(&out_, text, timeout); }

std::string Process::out() {
  std::lock_guard<std::mutex> lock(mutex_);
  return out_;
}

std::string Process::err() {
  std::lock_guard<std::mutex> lock(mutex_);
  return err_;
}

std::vector<std::string> Process::out_lines() {
  std::vector<std::string> lines;
  std::stringstream ss(out());
  std::string line;
  while (std::getline(ss, line)) lines.push_back(line);
  return lines;
}

std::string hitl_binary() {
  if (const char* env = std::getenv("HITL_BINARY_OVERRIDE")) return env;
  return HITL_BINARY;
}

RunResult run_hitl(const std::vector<std::string>& args, std::chrono::milliseconds timeout) {
  std::vector<std::string> argv{hitl_binary()};
  argv.insert(argv.end(), args.begin(), args.end());
  Process p(argv);
  const int code = p.wait(timeout);
  return {code, p.out(), p.err()};
}

uint16_t free_udp_port() {
  // The kernel may hand the same ephemeral port out again once it is closed: a test asking for its
  // HIL, client and local ports one after the other once got two equal ones ("--clients 55553 is
  // also the --local-port"). Never give one process the same port twice.
  static std::mutex mutex;
  static std::set<uint16_t> given;
  std::lock_guard<std::mutex> lock(mutex);
  for (int attempt = 0;; ++attempt) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in addr = loopback_address(0);
    ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
    socklen_t len = sizeof addr;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
    ::close(fd);
    const uint16_t port = ntohs(addr.sin_port);
    if (given.insert(port).second || attempt >= 100) return port;
  }
}

bool process_running(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const auto close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

std::string temp_dir() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "hitl-test-XXXXXX").string();
  if (::mkdtemp(tmpl.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return tmpl;
}

}  // namespace hitl::test
