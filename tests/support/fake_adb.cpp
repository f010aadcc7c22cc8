#include "tests/support/fake_adb.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "tests/support/process.h"

namespace hitl::test {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Running, not exited (a zombie whose parent has not reaped it yet counts as exited).
bool alive(pid_t pid) {
  const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
  const auto close_paren = stat.rfind(')');
  return close_paren != std::string::npos && close_paren + 2 < stat.size() && stat[close_paren + 2] != 'Z';
}

}  // namespace

FakeAdb::FakeAdb(const Options& options) : dir_(temp_dir()), old_path_(std::getenv("PATH") ? std::getenv("PATH") : "") {
  relay_port_ = options.relay_port ? options.relay_port : free_udp_port();
  root_ = dir_ + "/root";
  ::mkdir((dir_ + "/bin").c_str(), 0755);
  ::mkdir(root_.c_str(), 0755);
  ::mkdir((dir_ + "/root/bin").c_str(), 0755);
  if (::symlink(HITL_FAKE_ADB_SCRIPT, (dir_ + "/bin/adb").c_str()) != 0) throw std::runtime_error("symlink failed");
  ::setenv("FAKE_ADB_LOG", (dir_ + "/calls.log").c_str(), 1);
  ::setenv("FAKE_ADB_ROOT", (dir_ + "/root").c_str(), 1);
  ::setenv("FAKE_ADB_DEVICES", options.devices.c_str(), 1);
  ::setenv("FAKE_ADB_RELAY_PORT", std::to_string(relay_port_).c_str(), 1);
  ::setenv("FAKE_ADB_RELAY_ARGS", options.relay_args.c_str(), 1);
  ::setenv("PATH", (dir_ + "/bin:/usr/bin:/bin").c_str(), 1);
}

FakeAdb::~FakeAdb() {
  stop_relays();
  ::setenv("PATH", old_path_.c_str(), 1);
}

std::vector<std::string> FakeAdb::calls() const {
  std::vector<std::string> lines;
  std::istringstream in(read_file(dir_ + "/calls.log"));
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

int FakeAdb::find_call(const std::string& prefix, int from) const {
  const auto all = calls();
  for (int i = from; i < static_cast<int>(all.size()); ++i)
    if (all[static_cast<std::size_t>(i)].rfind(prefix, 0) == 0) return i;
  return -1;
}

void FakeAdb::install_relay_on_device(const std::string& relay_binary) const {
  if (::symlink(relay_binary.c_str(), (dir_ + "/root/bin/hitl-adb-relay").c_str()) != 0) throw std::runtime_error("symlink failed");
}

bool FakeAdb::pushed_relay_exists() const { return ::access((dir_ + "/root/tmp/hitl-adb-relay").c_str(), X_OK) == 0; }

std::string FakeAdb::relay_log() const { return read_file(dir_ + "/root/relay.log"); }

bool FakeAdb::stop_relays() {
  const std::string out = read_file(dir_ + "/root/shell.out");
  static const std::regex pid_re(R"(\(pid (\d+),)");
  bool all_stopped = true;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), pid_re); it != std::sregex_iterator(); ++it) {
    const pid_t pid = static_cast<pid_t>(std::stol((*it)[1]));
    if (::kill(pid, SIGTERM) != 0) continue;  // already gone
    bool gone = false;
    for (int i = 0; i < 500 && !gone; ++i) {
      gone = !alive(pid);
      if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!gone) {
      ::kill(pid, SIGKILL);
      all_stopped = false;
    }
  }
  return all_stopped;
}

void FakeAdb::make_board(const std::string& vision_hub_conf) const {
  for (const char* tool : {"dpkg", "dpkg-query", "systemctl", "systemd-run", "journalctl", "voxl-px4-hitl"})
    if (::symlink(HITL_FAKE_BOARD_SCRIPT, (root_ + "/bin/" + tool).c_str()) != 0) throw std::runtime_error("symlink failed");
  std::filesystem::create_directories(root_ + "/var/fake-board/services");
  std::filesystem::create_directories(root_ + "/var/fake-board/packages");
  std::filesystem::create_directories(root_ + "/etc/modalai");
  for (const char* service : {"voxl-px4", "voxl-vision-hub"}) std::ofstream(root_ + "/var/fake-board/services/" + service) << "enabled active\n";
  if (!vision_hub_conf.empty()) std::ofstream(root_ + "/etc/modalai/voxl-vision-hub.conf", std::ios::binary) << vision_hub_conf;
  std::ofstream(root_ + "/board.log");
}

std::vector<std::string> FakeAdb::board_calls() const {
  std::vector<std::string> lines;
  std::istringstream in(read_file(root_ + "/board.log"));
  std::string line;
  while (std::getline(in, line)) {
    for (auto at = line.find(root_); at != std::string::npos; at = line.find(root_)) line.erase(at, root_.size());
    lines.push_back(line);
  }
  return lines;
}

std::string FakeAdb::board_file(const std::string& path) const {
  std::ifstream in(root_ + path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool FakeAdb::board_file_exists(const std::string& path) const { return std::filesystem::exists(root_ + path); }

std::string FakeAdb::board_service(const std::string& name) const {
  std::string s = read_file(root_ + "/var/fake-board/services/" + name);
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

std::string FakeAdb::board_package(const std::string& name) const {
  std::string s = read_file(root_ + "/var/fake-board/packages/" + name);
  while (!s.empty() && s.back() == '\n') s.pop_back();
  return s;
}

NoAdbOnPath::NoAdbOnPath() : old_path_(std::getenv("PATH") ? std::getenv("PATH") : "") {
  ::setenv("PATH", (temp_dir() + ":/nonexistent").c_str(), 1);
}

NoAdbOnPath::~NoAdbOnPath() { ::setenv("PATH", old_path_.c_str(), 1); }

}  // namespace hitl::test
