#include "engine/px4/px4_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "base/common/clock.h"

extern char** environ;

namespace hitl::px4 {
namespace {

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

bool is_name_char(char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

}  // namespace

Expected<Px4Param> parse_px4_param(std::string_view text) {
  const auto eq = text.find('=');
  if (eq == std::string_view::npos)
    return Error::input("'" + std::string(text) + "' is not NAME=VALUE (e.g. MPC_THR_HOVER=0.6)");
  const std::string name(text.substr(0, eq)), value(text.substr(eq + 1));
  if (name.empty() || name.size() > 16 || !(name[0] >= 'A' && name[0] <= 'Z'))
    return Error::input("'" + name + "' is not a PX4 parameter name (capital letters, digits and _, at most 16, a letter first)");
  for (char c : name)
    if (!is_name_char(c))
      return Error::input("'" + name + "' is not a PX4 parameter name (capital letters, digits and _, at most 16, a letter first)");
  char* end = nullptr;
  errno = 0;
  const double v = value.empty() ? NAN : std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || errno == ERANGE || !std::isfinite(v))
    return Error::input(name + "=" + value + ": the value is not a finite number");
  return Px4Param{name, value};
}

std::string without_colour_codes(std::string_view line) {
  std::string out;
  out.reserve(line.size());
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\x1b' && i + 1 < line.size() && line[i + 1] == '[') {  // ESC [ ... letter
      i += 2;
      while (i < line.size() && !((line[i] >= 'A' && line[i] <= 'Z') || (line[i] >= 'a' && line[i] <= 'z'))) ++i;
      continue;
    }
    if (line[i] == '\r') continue;
    out += line[i];
  }
  return out;
}

std::optional<std::string> px4_unknown_parameter(std::string_view line) {
  const std::string_view before = "Parameter ", after = " not found";
  const auto at = line.find(before);
  if (at == std::string_view::npos) return std::nullopt;
  const auto end = line.find(after, at + before.size());
  if (end == std::string_view::npos || end == at + before.size()) return std::nullopt;
  return std::string(line.substr(at + before.size(), end - at - before.size()));
}

std::string without_shell_prompt(std::string line) {
  // A MAVLink shell (hitl shell) writes PX4's prompt into the console: "pxh> ERROR [...] ..."
  const std::string prompt = "pxh> ";
  std::size_t at = 0;
  while (line.compare(at, prompt.size(), prompt) == 0) at += prompt.size();
  return at == 0 ? line : line.substr(at);
}

std::optional<Severity> px4_console_severity(std::string_view raw) {
  const std::string line = without_shell_prompt(without_colour_codes(raw));
  if (line.rfind("ERROR", 0) == 0 || line.rfind("PANIC", 0) == 0) return Severity::Error;
  if (line.rfind("WARN", 0) == 0) return Severity::Warning;
  return std::nullopt;
}

std::vector<std::string> Px4Console::new_lines(std::size_t max_bytes) {
  std::vector<std::string> out;
  std::ifstream in(path_, std::ios::binary);
  if (!in) return out;
  in.seekg(static_cast<std::streamoff>(offset_));
  std::string chunk(max_bytes, '\0');
  in.read(chunk.data(), static_cast<std::streamsize>(max_bytes));
  chunk.resize(static_cast<std::size_t>(in.gcount()));
  offset_ += chunk.size();
  partial_ += chunk;
  std::size_t start = 0;
  for (std::size_t nl; (nl = partial_.find('\n', start)) != std::string::npos; start = nl + 1)
    out.push_back(without_shell_prompt(without_colour_codes(std::string_view(partial_).substr(start, nl - start))));
  partial_.erase(0, start);
  if (partial_.size() > 4096) {  // a line without end: given out in pieces, never held without bound
    out.push_back(without_colour_codes(partial_));
    partial_.clear();
  }
  return out;
}

std::vector<std::string> Px4Console::last_lines(std::size_t n) const {
  std::ifstream in(path_, std::ios::binary);
  std::deque<std::string> lines;
  if (!in) return {};
  in.seekg(0, std::ios::end);
  const auto size = static_cast<uint64_t>(in.tellg());
  const uint64_t from = size > 256 * 1024 ? size - 256 * 1024 : 0;  // the tail is enough
  in.seekg(static_cast<std::streamoff>(from));
  std::string line;
  while (std::getline(in, line)) {
    lines.push_back(without_colour_codes(line));
    if (lines.size() > n) lines.pop_front();
  }
  return {lines.begin(), lines.end()};
}

Expected<std::unique_ptr<Px4Process>> Px4Process::start(const Px4Build& build, const Px4StartOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(options.work_dir, ec);
  if (ec) return Error::unavailable("cannot create PX4's working folder '" + options.work_dir + "': " + ec.message());
  // Absolute: the child changes into the folder before PX4 starts, and PX4 takes -w from there (a
  // relative one made PX4 fail, or work in a folder inside the folder, where no report finds its ULog).
  const std::string work_dir = std::filesystem::absolute(options.work_dir, ec).string();
  if (ec) return Error::unavailable("cannot name PX4's working folder '" + options.work_dir + "': " + ec.message());
  const int console = ::open(options.console_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (console < 0)
    return Error::unavailable("cannot write PX4's console to '" + options.console_path + "': " + std::strerror(errno));
  const int null_in = ::open("/dev/null", O_RDONLY | O_CLOEXEC);

  // Everything the child needs is made before fork(): after it only async-signal-safe calls.
  std::map<std::string, std::string> env;
  for (char** e = environ; e != nullptr && *e != nullptr; ++e) {
    const std::string_view kv(*e);
    const auto eq = kv.find('=');
    if (eq == std::string_view::npos) continue;
    env[std::string(kv.substr(0, eq))] = std::string(kv.substr(eq + 1));
  }
  env.erase("PX4_SIM_HOSTNAME");
  env.erase("PX4_SIM_HOST_ADDR");
  env["PX4_SYS_AUTOSTART"] = "10016";
  env["PX4_SIM_MODEL"] = "none_iris";
  char speed[32];
  std::snprintf(speed, sizeof speed, "%g", options.speed_factor);
  env["PX4_SIM_SPEED_FACTOR"] = speed;
  for (const auto& p : options.params) env["PX4_PARAM_" + p.name] = p.value;
  std::vector<std::string> env_strings;
  for (const auto& [k, v] : env) env_strings.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (auto& s : env_strings) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> args = {build.program, "-d", "-i", std::to_string(options.instance.index), "-w",
                                   work_dir, build.etc_dir};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  int pid_pipe[2];
  if (::pipe2(pid_pipe, O_CLOEXEC) != 0) {
    const int err = errno;
    ::close(console);
    if (null_in >= 0) ::close(null_in);
    return Error::unavailable(std::string("cannot start PX4: pipe: ") + std::strerror(err));
  }

  // hitl -> a supervisor (a fork of hitl that never execs, in a process group of its own) -> PX4 in a
// process group of its own.
  // PX4 runs its start script in a shell that starts PX4's modules as client processes; killed with
  // PX4 alone (PR_SET_PDEATHSIG reaches only a direct child), that shell went on and started them in
  // the next PX4 of the same instance. The supervisor dies with hitl and then kills PX4's whole
  // group; when PX4 exits it kills what PX4 left in its group and exits with PX4's code.
  const pid_t supervisor = ::fork();
  if (supervisor < 0) {
    const int err = errno;
    ::close(console);
    if (null_in >= 0) ::close(null_in);
    ::close(pid_pipe[0]);
    ::close(pid_pipe[1]);
    return Error::unavailable(std::string("cannot start PX4: fork: ") + std::strerror(err));
  }
  if (supervisor == 0) {
    // A group of its own too (set by both sides of the fork, so that neither order races): a kill
    // of hitl's process group (a campaign's runner kills a flight past its time limit that way)
    // must leave the supervisor to see hitl die and kill PX4, not take it along and orphan PX4.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGUSR2);
    if (::getppid() != parent) ::_exit(127);
    // hitl's other descriptors (its sockets) are not the supervisor's to hold.
    for (int fd = 3; fd < 4096; ++fd)
      if (fd != console && fd != null_in && fd != pid_pipe[1]) ::close(fd);
    sigset_t all;
    ::sigfillset(&all);
    ::sigprocmask(SIG_BLOCK, &all, nullptr);  // nothing interrupts the fork below
    const pid_t px4 = ::fork();
    if (px4 < 0) ::_exit(127);
    if (px4 == 0) {
      ::setpgid(0, 0);  // its own group: a Ctrl-C at hitl's terminal is hitl's to handle
      sigset_t none;
      ::sigemptyset(&none);
      ::sigprocmask(SIG_SETMASK, &none, nullptr);
      struct sigaction dfl {};
      dfl.sa_handler = SIG_DFL;
      ::sigaction(SIGUSR2, &dfl, nullptr);
      if (null_in >= 0) ::dup2(null_in, 0);
      ::dup2(console, 1);
      ::dup2(console, 2);
      if (::chdir(options.work_dir.c_str()) != 0) ::_exit(127);
      ::execve(argv[0], argv.data(), envp.data());
      ::_exit(127);
    }
    ::setpgid(px4, px4);
    const int32_t px4_pid = px4;
    (void)!::write(pid_pipe[1], &px4_pid, sizeof px4_pid);
    ::close(pid_pipe[1]);
    // Wait for PX4's end or hitl's: SIGCHLD or SIGUSR2 (PR_SET_PDEATHSIG), taken synchronously.
    sigset_t wanted;
    ::sigemptyset(&wanted);
    ::sigaddset(&wanted, SIGCHLD);
    ::sigaddset(&wanted, SIGUSR2);
    for (;;) {
      int status = 0;
      const pid_t done = ::waitpid(px4, &status, WNOHANG);
      if (done == px4) {
        ::kill(-px4, SIGKILL);  // what PX4 left in its group
        ::_exit(WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 127);
      }
      if (::getppid() != parent) {  // hitl is gone (its SIGUSR2 may have come before the check above)
        ::kill(-px4, SIGKILL);
        ::_exit(128 + SIGKILL);
      }
      int sig = 0;
      ::sigwait(&wanted, &sig);
    }
  }
  ::setpgid(supervisor, supervisor);
  ::close(console);
  if (null_in >= 0) ::close(null_in);
  ::close(pid_pipe[1]);
  int32_t px4_pid = -1;
  ssize_t got = -1;
  do {
    got = ::read(pid_pipe[0], &px4_pid, sizeof px4_pid);
  } while (got < 0 && errno == EINTR);
  ::close(pid_pipe[0]);
  if (got != static_cast<ssize_t>(sizeof px4_pid) || px4_pid <= 0) {
    int status = 0;
    ::waitpid(supervisor, &status, 0);
    return Error::unavailable("cannot start PX4: its supervisor process failed");
  }
  return std::unique_ptr<Px4Process>(new Px4Process(px4_pid, supervisor, options));
}

std::optional<int> Px4Process::exited() {
  if (exit_code_) return exit_code_;
  int status = 0;
  const pid_t r = ::waitpid(supervisor_, &status, WNOHANG);
  if (r == supervisor_) exit_code_ = exit_code_of(status);
  return exit_code_;
}

int Px4Process::stop(bool kill_now, double grace_s) {
  if (exited()) return *exit_code_;
  ::kill(-pid_, kill_now ? SIGKILL : SIGTERM);  // its group: PX4 and anything it started
  const double deadline_s = monotonic_s() + (kill_now ? 5.0 : grace_s);
  while (!exited() && monotonic_s() < deadline_s) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!exited()) {
    ::kill(-pid_, SIGKILL);
    int status = 0;
    if (::waitpid(supervisor_, &status, 0) == supervisor_) exit_code_ = exit_code_of(status);
    else exit_code_ = 128 + SIGKILL;
  }
  return *exit_code_;
}

Px4Process::~Px4Process() { stop(true); }

}  // namespace hitl::px4
