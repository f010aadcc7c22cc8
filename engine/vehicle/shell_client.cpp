#include "engine/vehicle/shell_client.h"

#include <algorithm>

#include "base/mavlink/messages.h"
#include "engine/vehicle/board_replies.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
constexpr uint8_t kDevShell = 10;
constexpr uint8_t kFlagRespond = 2;
constexpr uint8_t kFlagExclusive = 4;

}  // namespace

void ShellClient::send_text(const std::string& text) {
  for (std::size_t pos = 0; pos < text.size(); pos += 70) {
    msg::SerialControl m;
    m.device = kDevShell;
    m.flags = kFlagRespond | kFlagExclusive;
    const std::size_t n = std::min<std::size_t>(70, text.size() - pos);
    m.count = static_cast<uint8_t>(n);
    std::copy_n(reinterpret_cast<const uint8_t*>(text.data() + pos), n, m.data.begin());
    link_.send(m);
  }
}

Expected<std::string> ShellClient::run(const std::string& line, double timeout_s) {
  // First an empty line, to find the prompt and drain anything an earlier session left.
  ShellOutput out;
  auto collect = [&](const mavlink::Frame& f) { return f.is<msg::SerialControl>() && out.append(f.as<msg::SerialControl>()); };
  send_text("\n");
  if (!link_.wait(timeout_s, collect)) return Error::failed("the shell did not answer (SERIAL_CONTROL device 10) within " + std::to_string(static_cast<int>(timeout_s)) + " s");
  out.clear();
  send_text(line + "\n");
  if (!link_.wait(timeout_s, collect)) return Error::failed("'" + line + "' did not finish within " + std::to_string(static_cast<int>(timeout_s)) + " s; output so far:\n" + out.text());
  // Drop the echoed command line and the final prompt.
  return out.body();
}

}  // namespace hitl::vehicle
