// The board's MAVLink shell: SERIAL_CONTROL on device 10 (SERIAL_CONTROL_DEV_SHELL), as PX4's
// mavlink_shell.py drives it. Input bytes are echoed and collected into lines; each line runs a
// command and its output comes back in SERIAL_CONTROL replies of up to 70 bytes, then the prompt.
// A command that returns non-zero is followed by the line PX4's shell (pxh) prints for it:
// "Command 'NAME' failed, returned N." (NAME: the line's first word).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "base/mavlink/messages.h"

namespace hitl::target {

inline constexpr uint8_t kSerialControlDevShell = 10;
inline constexpr uint8_t kSerialControlFlagReply = 1;
inline constexpr const char* kShellPrompt = "pxh> ";

/// What one command line printed (lines ending in '\n') and returned.
struct ShellResult {
  ShellResult(std::string text = {}, int return_code = 0) : output(std::move(text)), status(return_code) {}
  ShellResult(const char* text, int return_code = 0) : ShellResult(std::string(text), return_code) {}
  std::string output;
  int status = 0;
};

class Shell {
 public:
  /// Runs one command line.
  using Executor = std::function<ShellResult(const std::string& line)>;
  explicit Shell(Executor executor) : executor_(std::move(executor)) {}

  /// Takes one SERIAL_CONTROL; returns the replies to send (empty when not for the shell).
  std::vector<mavlink::msg::SerialControl> on_serial_control(const mavlink::msg::SerialControl& in);
  uint64_t commands_run() const { return commands_run_; }

  /// Splits text into SERIAL_CONTROL replies.
  static std::vector<mavlink::msg::SerialControl> replies(const std::string& text);

 private:
  Executor executor_;
  std::string line_;
  uint64_t commands_run_ = 0;
};

}  // namespace hitl::target
