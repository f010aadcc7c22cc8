#include "emulator/shell.h"

#include <algorithm>

namespace hitl::target {

std::vector<mavlink::msg::SerialControl> Shell::replies(const std::string& text) {
  std::vector<mavlink::msg::SerialControl> out;
  for (std::size_t pos = 0; pos < text.size(); pos += 70) {
    mavlink::msg::SerialControl m;
    m.device = kSerialControlDevShell;
    m.flags = kSerialControlFlagReply;
    const std::size_t n = std::min<std::size_t>(70, text.size() - pos);
    m.count = static_cast<uint8_t>(n);
    std::copy_n(reinterpret_cast<const uint8_t*>(text.data() + pos), n, m.data.begin());
    out.push_back(m);
  }
  return out;
}

std::vector<mavlink::msg::SerialControl> Shell::on_serial_control(const mavlink::msg::SerialControl& in) {
  if (in.device != kSerialControlDevShell) return {};
  std::string output;
  const std::size_t n = std::min<std::size_t>(in.count, in.data.size());
  for (std::size_t i = 0; i < n; ++i) {
    const char c = static_cast<char>(in.data[i]);
    if (c == '\r') continue;
    if (c == '\n') {
      output += "\n";
      const auto first = line_.find_first_not_of(' ');
      if (first != std::string::npos) {
        ++commands_run_;
        const std::string command = line_.substr(first);
        const ShellResult result = executor_(command);
        output += result.output;
        if (result.status != 0)
          output += "Command '" + command.substr(0, command.find(' ')) + "' failed, returned " + std::to_string(result.status) + ".\n";
      }
      output += kShellPrompt;
      line_.clear();
    } else if (c == 0x7F || c == '\b') {
      if (!line_.empty()) line_.pop_back();
    } else if (static_cast<unsigned char>(c) >= 0x20 && line_.size() < 256) {
      line_ += c;
      output += c;  // echo, as nsh does
    }
  }
  if (n == 0) output += kShellPrompt;  // an empty poll asks for the prompt
  return replies(output);
}

}  // namespace hitl::target
