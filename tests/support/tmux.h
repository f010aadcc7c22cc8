// A terminal for end-to-end tests: a detached session of a private tmux server (its own socket
// name, so nothing of the user's tmux is touched); keys go in with send-keys, the screen comes
// back with capture-pane.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/process.h"

namespace hitl::test {

/// tmux's path, or empty when it is not installed.
inline std::string tmux_path() {
  FILE* p = ::popen("command -v tmux 2>/dev/null", "r");
  if (p == nullptr) return {};
  char buf[512] = {};
  const bool got = std::fgets(buf, sizeof buf, p) != nullptr;
  ::pclose(p);
  std::string path = got ? buf : "";
  while (!path.empty() && (path.back() == '\n' || path.back() == '\r')) path.pop_back();
  return path;
}

/// `s` as one single-quoted shell word.
inline std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

class Tmux {
 public:
  Tmux(std::string path, const std::string& name)
      : path_(std::move(path)), socket_("hitl-" + name + "-" + std::to_string(::getpid())) {}
  ~Tmux() { run({"kill-server"}); }
  Tmux(const Tmux&) = delete;
  Tmux& operator=(const Tmux&) = delete;

  std::string run(const std::vector<std::string>& args) {
    std::vector<std::string> argv{path_, "-L", socket_};
    argv.insert(argv.end(), args.begin(), args.end());
    Process p(argv);
    p.wait(std::chrono::seconds(10));
    return p.out();
  }
  /// A window of `columns` x `rows` running the shell command `command`.
  void start(const std::string& command, int columns = 120, int rows = 40) {
    run({"new-session", "-d", "-s", "t", "-x", std::to_string(columns), "-y", std::to_string(rows), command});
  }
  std::string screen() { return run({"capture-pane", "-p", "-t", "t"}); }
  /// tmux key names ("Up", "C-r", "Enter") or literal text.
  void keys(const std::vector<std::string>& k) {
    std::vector<std::string> args{"send-keys", "-t", "t"};
    args.insert(args.end(), k.begin(), k.end());
    run(args);
  }
  /// Polls the screen until `done(screen)`, up to `timeout`; the last screen either way.
  bool until(const std::function<bool(const std::string&)>& done, std::chrono::milliseconds timeout, std::string* last) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      *last = screen();
      if (done(*last)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    *last = screen();
    return done(*last);
  }

 private:
  std::string path_;
  std::string socket_;
};

/// The screen's last line that is not blank.
inline std::string last_line(const std::string& screen) {
  std::size_t end = screen.find_last_not_of(" \n");
  if (end == std::string::npos) return {};
  const std::size_t start = screen.rfind('\n', end);
  return screen.substr(start == std::string::npos ? 0 : start + 1, end + 1 - (start == std::string::npos ? 0 : start + 1));
}

}  // namespace hitl::test
