#include "engine/net/adb_client.h"

#include <sstream>

#include "engine/net/socket_address.h"

namespace hitl::net {
namespace {

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

/// adb's own message from a failed call: its stderr, else its stdout, on one line.
std::string adb_message(const ProgramOutput& out) {
  std::string text = trim(out.err.empty() ? out.out : out.err);
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text.empty() ? "no message" : text;
}

}  // namespace

std::vector<AdbDevice> parse_adb_devices(std::string_view output) {
  std::vector<AdbDevice> devices;
  std::istringstream in{std::string(output)};
  std::string line;
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty() || line[0] == '*' || line.rfind("List of devices", 0) == 0 || line.rfind("adb server", 0) == 0) continue;
    const auto gap = line.find_first_of(" \t");
    if (gap == std::string::npos) continue;
    AdbDevice d;
    d.serial = line.substr(0, gap);
    std::string rest = trim(line.substr(gap));
    // "no permissions (user in plugdev group; ...)" is a state of two words; -l adds "usb:1-1 product:..".
    if (rest.rfind("no permissions", 0) == 0) d.state = "no permissions";
    else d.state = rest.substr(0, rest.find_first_of(" \t"));
    devices.push_back(std::move(d));
  }
  return devices;
}

std::string explain_adb_state(const AdbDevice& d) {
  if (d.state == "device") return d.serial + " is ready";
  if (d.state == "unauthorized")
    return d.serial + " is unauthorized: adb's key is not accepted by the board; restart adb (adb kill-server) and check "
                      "`adb devices` again";
  if (d.state == "offline") return d.serial + " is offline: unplug and replug the board's USB-C cable, or wait for it to finish booting";
  if (d.state == "no permissions")
    return d.serial + " has no permissions: this user may not open the USB device; add a udev rule for it "
                      "(docs/adb.md) or run `sudo adb kill-server; sudo adb start-server`";
  if (d.state == "recovery" || d.state == "bootloader" || d.state == "sideload")
    return d.serial + " is in " + d.state + " mode, not running its system";
  return d.serial + " is '" + d.state + "'";
}

Expected<std::string> find_adb() {
  if (auto path = find_on_path("adb")) return *path;
  return Error::failed("adb not found on PATH: install the Debian package adb (sudo apt-get install adb), which also brings "
                       "the udev rules for USB access");
}

Expected<AdbDevices> list_adb_devices() {
  auto path = find_adb();
  if (!path) return path.error();
  auto out = run_program(*path, {"devices"}, kAdbCommandTimeout_ms);
  if (!out) return out.error();
  if (out->exit_code != 0)
    return Error::failed("'" + *path + " devices' failed (exit " + std::to_string(out->exit_code) + "): " + adb_message(*out));
  return AdbDevices{*path, parse_adb_devices(out->out)};
}

Expected<std::string> choose_adb_device(const std::vector<AdbDevice>& devices, std::string_view serial) {
  if (!serial.empty()) {
    for (const auto& d : devices) {
      if (d.serial != serial) continue;
      if (d.ready()) return d.serial;
      return Error::failed("--adb-serial " + std::string(serial) + ": " + explain_adb_state(d));
    }
    std::string listed;
    for (const auto& d : devices) listed += (listed.empty() ? "" : ", ") + d.serial + " (" + d.state + ")";
    return Error::failed("--adb-serial " + std::string(serial) + ": no such device attached (`adb devices` lists " +
                         (listed.empty() ? std::string("none") : listed) + ")");
  }
  std::vector<const AdbDevice*> ready;
  for (const auto& d : devices)
    if (d.ready()) ready.push_back(&d);
  if (ready.size() == 1) return ready.front()->serial;
  if (ready.size() > 1) {
    std::string listed;
    for (const auto* d : ready) listed += (listed.empty() ? "" : ", ") + d->serial;
    return Error::failed(std::to_string(ready.size()) + " devices are attached to adb (" + listed + "): choose the board with --adb-serial SERIAL");
  }
  if (devices.empty())
    return Error::failed("no board attached to adb: plug in the VOXL2's USB-C cable and check that `adb devices` lists it");
  std::string why;
  for (const auto& d : devices) why += (why.empty() ? "" : "; ") + explain_adb_state(d);
  return Error::failed("no adb device is ready: " + why);
}

Expected<Adb> Adb::connect(std::string_view serial) {
  auto listed = list_adb_devices();
  if (!listed) return listed.error();
  auto chosen = choose_adb_device(listed->devices, serial);
  if (!chosen) return chosen.error();
  return Adb(listed->adb_path, *chosen);
}

bool adb_connected(std::string_view output) {
  return output.find("connected to ") != std::string_view::npos && output.find("failed to connect") == std::string_view::npos &&
         output.find("cannot connect") == std::string_view::npos;
}

Expected<Adb> Adb::connect_network(const std::string& host, uint16_t port) {
  auto path = find_adb();
  if (!path) return path.error();
  const std::string target = host + ":" + std::to_string(port);
  auto out = run_program(*path, {"connect", target}, kAdbCommandTimeout_ms);
  if (!out) return out.error();
  if (out->exit_code != 0 || !adb_connected(out->out + out->err))
    return Error::failed("adb connect " + target + ": " + adb_message(*out) + " (the board listens for adb over the network after `adb tcpip " +
                         std::to_string(kAdbTcpPort) + "` over USB; or use --adb for USB)");
  return Adb(*path, target);
}

Expected<ProgramOutput> Adb::run(const std::vector<std::string>& args, int timeout_ms) const {
  std::vector<std::string> full{"-s", serial_};
  full.insert(full.end(), args.begin(), args.end());
  auto out = run_program(path_, full, timeout_ms);
  if (!out) return out.error();
  if (out->exit_code != 0)
    return Error::failed("'" + command_line("adb", full) + "' failed (exit " + std::to_string(out->exit_code) + "): " + adb_message(*out) +
                         " (is the board still attached? `adb devices`)");
  return out;
}

Expected<uint16_t> Adb::forward(uint16_t remote_port) const {
  auto out = run({"forward", "tcp:0", "tcp:" + std::to_string(remote_port)});
  if (!out) return out.error();
  // adb prints the local port it chose ("41235\n").
  auto port = parse_port(trim(out->out), "the port `adb forward tcp:0` printed");
  if (!port) return port.error().suffixed(" (adb printed '" + trim(out->out) + "')");
  return *port;
}

Status Adb::remove_forward(uint16_t local_port) const {
  auto out = run({"forward", "--remove", "tcp:" + std::to_string(local_port)});
  if (!out) return out.error();
  return Ok{};
}

Status Adb::push(const std::string& local_path, const std::string& remote_path) const {
  auto out = run({"push", local_path, remote_path}, kAdbPushTimeout_ms);
  if (!out) return out.error();
  return Ok{};
}

Expected<ProgramOutput> Adb::shell(const std::string& command, int timeout_ms) const {
  std::vector<std::string> full{"-s", serial_, "shell", command};
  return run_program(path_, full, timeout_ms);
}

}  // namespace hitl::net
