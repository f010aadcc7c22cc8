// The board's Linux side as `hitl board` uses it: run a shell command, push a file. adb is the one
// way in (engine/net/adb_client.h); tests give a scripted board.
#pragma once

#include <string>

#include "base/common/expected.h"
#include "engine/net/adb_client.h"

namespace hitl::board {

class BoardShell {
 public:
  virtual ~BoardShell() = default;
  /// Runs `command` with the board's /bin/sh: its output and exit code; an Error only when the
  /// command could not be run at all (adb missing, the device gone).
  virtual Expected<net::ProgramOutput> run(const std::string& command) = 0;
  /// Copies the host file `local_path` to `remote_path` on the board.
  virtual Status push(const std::string& local_path, const std::string& remote_path) = 0;
  /// "adb device 7f3a9c0d"
  virtual std::string describe() const = 0;
};

/// Through adb, on one device.
class AdbBoardShell : public BoardShell {
 public:
  explicit AdbBoardShell(net::Adb adb) : adb_(std::move(adb)) {}
  Expected<net::ProgramOutput> run(const std::string& command) override;
  Status push(const std::string& local_path, const std::string& remote_path) override;
  std::string describe() const override { return "adb device " + adb_.serial(); }

 private:
  net::Adb adb_;
};

}  // namespace hitl::board
