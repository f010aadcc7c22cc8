// adb (the Android Debug Bridge) as hitl uses it to reach a VOXL2 over USB: finding the program,
// the attached devices, port forwards, push and shell. Every failure is an Error that says what to
// install, plug in or run.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/child_process.h"

namespace hitl::net {

/// How long one adb call may take (the first one also starts adb's server).
inline constexpr int kAdbCommandTimeout_ms = 15000;
/// `adb push` of the relay (a few hundred kB over USB 2).
inline constexpr int kAdbPushTimeout_ms = 60000;

/// One line of `adb devices`: a serial and its state ("device" when ready; "unauthorized",
/// "offline", "no permissions", ...).
struct AdbDevice {
  std::string serial;
  std::string state;
  bool ready() const { return state == "device"; }
};

/// `adb devices` output, parsed: the "List of devices attached" header and the server's
/// "* daemon ..." lines are skipped; `-l`'s extra fields are ignored.
std::vector<AdbDevice> parse_adb_devices(std::string_view output);

/// What a device's state means and what to do about it, for messages.
std::string explain_adb_state(const AdbDevice& device);

/// The path of `adb` on $PATH; when it is not there, an Error naming the Debian package to install.
Expected<std::string> find_adb();

/// Is adb installed, and which devices are attached. An Error only when adb is missing or fails;
/// no device attached is an empty list. (`hitl doctor --adb` calls this.)
struct AdbDevices {
  std::string adb_path;
  std::vector<AdbDevice> devices;
};
Expected<AdbDevices> list_adb_devices();

/// The device to talk to: `serial` when given (it must be attached and ready), else the only ready
/// one. The Error says to plug in the board, to pick one with --adb-serial, or what the state means.
Expected<std::string> choose_adb_device(const std::vector<AdbDevice>& devices, std::string_view serial);

/// adbd's TCP port on a board reached over the network (`adb tcpip 5555` once over USB).
inline constexpr uint16_t kAdbTcpPort = 5555;

/// Whether `adb connect HOST:PORT`'s output says it is connected ("connected to ...", "already
/// connected to ..."); adb exits 0 on "failed to connect" too, so its words decide.
bool adb_connected(std::string_view output);

/// adb bound to one device: every call runs `adb -s SERIAL ...`.
class Adb {
 public:
  /// Finds adb, lists the devices and picks one (choose_adb_device).
  static Expected<Adb> connect(std::string_view serial);
  /// Over the network: `adb connect HOST:PORT`, then the device HOST:PORT. The Error says what adb
  /// answered and how to make the board listen (`adb tcpip 5555` over USB) or to use USB instead.
  static Expected<Adb> connect_network(const std::string& host, uint16_t port = kAdbTcpPort);
  Adb(std::string adb_path, std::string serial) : path_(std::move(adb_path)), serial_(std::move(serial)) {}

  const std::string& serial() const { return serial_; }
  const std::string& path() const { return path_; }

  /// `adb forward tcp:0 tcp:REMOTE`: adb picks a free local port and prints it; that port.
  Expected<uint16_t> forward(uint16_t remote_port) const;
  /// `adb forward --remove tcp:LOCAL`.
  Status remove_forward(uint16_t local_port) const;
  /// `adb push LOCAL REMOTE`.
  Status push(const std::string& local_path, const std::string& remote_path) const;
  /// `adb shell COMMAND`: what it printed and its exit code (adb passes the exit code through).
  Expected<ProgramOutput> shell(const std::string& command, int timeout_ms = kAdbCommandTimeout_ms) const;
  /// `adb -s SERIAL ARGS...`; an Error when adb cannot run or exits non-zero, with its message.
  Expected<ProgramOutput> run(const std::vector<std::string>& args, int timeout_ms = kAdbCommandTimeout_ms) const;

 private:
  std::string path_;
  std::string serial_;
};

}  // namespace hitl::net
