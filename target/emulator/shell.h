// The board's MAVLink shell: SERIAL_CONTROL on device 10 (SERIAL_CONTROL_DEV_SHELL), as PX4's
// mavlink_shell.py drives it. Input bytes are echoed and collected into lines; each line runs a
// command and its output comes back in SERIAL_CONTROL replies of up to 70 bytes, then the prompt.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/mavlink/messages.h"

namespace hitl::target {

inline constexpr uint8_t kSerialControlDevShell = 10;
inline constexpr uint8_t kSerialControlFlagReply = 1;
inline constexpr const char* kShellPrompt = "pxh> ";

class Shell {
 public:
  /// Runs one command line and returns its output (lines ending in '\n').
  using Executor = std::function<std::string(const std::string& line)>;
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
