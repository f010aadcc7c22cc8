#include "engine/vehicle/command_client.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstring>
#include <optional>

#include "base/common/clock.h"
#include "base/mavlink/text_field.h"
#include "engine/mavlink/statustext.h"

namespace hitl::vehicle {
namespace {
namespace msg = mavlink::msg;
}

std::string to_string(mavlink::MavResult r) {
  switch (r) {
    case mavlink::MavResult::Accepted: return "accepted";
    case mavlink::MavResult::TemporarilyRejected: return "temporarily rejected";
    case mavlink::MavResult::Denied: return "denied";
    case mavlink::MavResult::Unsupported: return "unsupported";
    case mavlink::MavResult::Failed: return "failed";
    case mavlink::MavResult::InProgress: return "in progress";
    case mavlink::MavResult::Cancelled: return "cancelled";
  }
  return "result " + std::to_string(static_cast<int>(r));
}

std::string CommandOutcome::text() const {
  std::string out = to_string(result);
  if (!accepted() && !statustexts.empty()) out += ": " + statustexts.back();
  return out;
}

bool CommandOutcome::pending() const {
  if (result != mavlink::MavResult::TemporarilyRejected && result != mavlink::MavResult::Denied) return false;
  std::string t = text();
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* word : {"preflight", "not ready", "ekf", "gps", "aligned", "estimat", "pending", "calibrat"})
    if (t.find(word) != std::string::npos) return true;
  return false;
}

Expected<CommandOutcome> CommandClient::send(uint16_t command, const std::array<float, 7>& p, double timeout_s, int retries,
                                             double in_progress_limit_s) {
  msg::CommandLong c;
  c.target_system = link_.target_sysid();
  c.target_component = link_.target_compid();
  c.command = command;
  c.param1 = p[0]; c.param2 = p[1]; c.param3 = p[2]; c.param4 = p[3]; c.param5 = p[4]; c.param6 = p[5]; c.param7 = p[6];
  CommandOutcome outcome;
  std::optional<uint8_t> result;
  mavlink::StatusTextAssembler statustexts;  // PX4 sends a long refusal in chunks
  auto handler = [&](const mavlink::Frame& f) {
    if (f.is<msg::Statustext>()) {
      for (const auto& t : statustexts.on_frame(f, monotonic_s()))
        outcome.statustexts.push_back(mavlink::printable_statustext(t.text));
      return false;
    }
    if (!f.is<msg::CommandAck>()) return false;
    const auto a = f.as<msg::CommandAck>();
    if (a.command != command) return false;
    result = a.result;
    return a.result != static_cast<uint8_t>(mavlink::MavResult::InProgress);
  };
  for (int attempt = 0; attempt < retries; ++attempt) {
    c.confirmation = static_cast<uint8_t>(attempt);
    link_.send(c);
    if (link_.wait(timeout_s, handler)) break;
    if (result == static_cast<uint8_t>(mavlink::MavResult::InProgress)) {  // the board is on it: wait, don't resend
      link_.wait(in_progress_limit_s, handler);
      break;
    }
  }
  if (!result) return Error::failed("no COMMAND_ACK for command " + std::to_string(command) + " after " + std::to_string(retries) + " tries");
  outcome.result = static_cast<mavlink::MavResult>(*result);
  // STATUSTEXTs often trail the ACK by a moment: give them a chance to arrive.
  if (!outcome.accepted()) link_.wait(0.2, handler);
  for (const auto& t : statustexts.flush()) outcome.statustexts.push_back(mavlink::printable_statustext(t.text));
  return outcome;
}

}  // namespace hitl::vehicle
