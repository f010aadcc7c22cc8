// The stand-in adb (tests/support/fake_adb.sh) first on $PATH for one test: its calls recorded, the
// "board" this machine, relays it starts stopped (SIGTERM) when the test ends.
#pragma once

#include <string>
#include <vector>

namespace hitl::test {

class FakeAdb {
 public:
  struct Options {
    std::string devices = "FAKE0001 device";  ///< FAKE_ADB_DEVICES
    uint16_t relay_port = 0;                   ///< FAKE_ADB_RELAY_PORT (0: a free one)
    std::string relay_args;                    ///< FAKE_ADB_RELAY_ARGS
  };
  explicit FakeAdb(const Options& options);
  ~FakeAdb();
  FakeAdb(const FakeAdb&) = delete;
  FakeAdb& operator=(const FakeAdb&) = delete;

  /// Every call so far, one string of arguments each ("-s FAKE0001 forward tcp:0 tcp:14590").
  std::vector<std::string> calls() const;
  /// The index of the first call at or after `from` that starts with `prefix`, or -1.
  int find_call(const std::string& prefix, int from = 0) const;
  /// Puts a hitl-adb-relay on the device's PATH (the board package installed).
  void install_relay_on_device(const std::string& relay_binary) const;
  bool pushed_relay_exists() const;
  /// The relays it started (pids from their "listening ... (pid N" line); stops them and waits.
  bool stop_relays();
  std::string relay_log() const;
  /// Makes the device a VOXL2 for hitl board (fake_board.sh): dpkg, dpkg-query, systemctl,
  /// systemd-run, journalctl and voxl-px4-hitl on its PATH; ModalAI's voxl-px4 and voxl-vision-hub
  /// enabled and running; `vision_hub_conf` as /etc/modalai/voxl-vision-hub.conf (none when empty).
  void make_board(const std::string& vision_hub_conf) const;
  /// The board programs' calls so far, one line each, the device root taken out of paths.
  std::vector<std::string> board_calls() const;
  /// A file on the device ("/etc/modalai/voxl-vision-hub.conf"); empty when absent.
  std::string board_file(const std::string& path) const;
  bool board_file_exists(const std::string& path) const;
  /// "enabled active" (the stand-in systemctl's state), empty when the unit does not exist.
  std::string board_service(const std::string& name) const;
  std::string board_package(const std::string& name) const;
  const std::string& root() const { return root_; }
  uint16_t relay_port() const { return relay_port_; }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::string root_;
  std::string old_path_;
  uint16_t relay_port_ = 0;
};

/// A directory with no adb in it, as $PATH.
class NoAdbOnPath {
 public:
  NoAdbOnPath();
  ~NoAdbOnPath();

 private:
  std::string old_path_;
};

}  // namespace hitl::test
