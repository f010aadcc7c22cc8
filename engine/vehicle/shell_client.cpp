#include "engine/vehicle/shell_client.h"

#include <algorithm>

#include "engine/mavlink/messages.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
constexpr uint8_t kDevShell = 10;
constexpr uint8_t kFlagRespond = 2;
constexpr uint8_t kFlagExclusive = 4;

bool ends_with_prompt(const std::string& s) {
  for (const char* prompt : {"pxh> ", "nsh> "}) {
    const std::string p(prompt);
    if (s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0) return true;
  }
  return false;
}

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
  std::string out;
  auto collect = [&](const mavlink::Frame& f) {
    if (!f.is<msg::SerialControl>()) return false;
    const auto r = f.as<msg::SerialControl>();
    if (r.device != kDevShell) return false;
    out.append(reinterpret_cast<const char*>(r.data.data()), std::min<std::size_t>(r.count, r.data.size()));
    return ends_with_prompt(out);
  };
  send_text("\n");
  if (!link_.wait(timeout_s, collect)) return Error{"the shell did not answer (SERIAL_CONTROL device 10) within " + std::to_string(static_cast<int>(timeout_s)) + " s"};
  out.clear();
  send_text(line + "\n");
  if (!link_.wait(timeout_s, collect)) return Error{"'" + line + "' did not finish within " + std::to_string(static_cast<int>(timeout_s)) + " s; output so far:\n" + out};
  // Drop the echoed command line and the final prompt.
  const auto first_newline = out.find('\n');
  std::string body = first_newline == std::string::npos ? std::string() : out.substr(first_newline + 1);
  for (const char* prompt : {"pxh> ", "nsh> "})
    if (body.size() >= 5 && body.compare(body.size() - 5, 5, prompt) == 0) body.resize(body.size() - 5);
  return body;
}

}  // namespace hitl::vehicle
