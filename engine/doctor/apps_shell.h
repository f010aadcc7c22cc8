// A shell on the board's apps processor (Linux), for the VIO checks: `adb shell` when doctor runs
// with --adb and adb lists the board; otherwise PX4's MAVLink shell, which runs only PX4 commands
// (the emulated board, hitl target, also answers `voxl-hitl-vio-server --status`, since its VIO
// listener is that server). Commands it cannot run come back as an Error saying why, which the
// checks turn into a skip.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/net/adb_client.h"

namespace hitl::doctor {

class AppsShell {
 public:
  /// Runs a PX4 shell line (the MAVLink shell), or an Error.
  using Px4Shell = std::function<Expected<std::string>(const std::string&)>;

  /// Through adb, on the device chosen by the adb check.
  static AppsShell adb(net::Adb adb);
  /// Through PX4's shell; none when there is no link to the board (`why`).
  static AppsShell px4(Px4Shell shell);
  static AppsShell none(std::string why);

  bool is_adb() const { return adb_.has_value(); }
  /// Runs `command` on the apps processor. `px4_answers`: whether PX4's shell can run it at all
  /// (only voxl-hitl-vio-server's status, and only on the emulated board).
  Expected<std::string> run(const std::string& command, bool px4_answers) const;

 private:
  std::optional<net::Adb> adb_;
  Px4Shell px4_;
  std::string none_;
};

}  // namespace hitl::doctor
