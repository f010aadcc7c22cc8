#include "tui/message_log.h"

#include "engine/common/clock.h"
#include "engine/mavlink/enums.h"

namespace hitl::tui {

Severity severity_from_mavlink(uint8_t mav_severity) {
  using mavlink::MavSeverity;
  if (mav_severity <= static_cast<uint8_t>(MavSeverity::Error)) return Severity::Error;
  if (mav_severity == static_cast<uint8_t>(MavSeverity::Warning)) return Severity::Warning;
  if (mav_severity == static_cast<uint8_t>(MavSeverity::Notice)) return Severity::Notice;
  return Severity::Info;
}

MessageLog::MessageLog() : start_s_(monotonic_s()) {}

void MessageLog::set_clock(std::function<double()> clock_s) {
  std::lock_guard<std::mutex> lock(mutex_);
  clock_s_ = std::move(clock_s);
}

void MessageLog::add(Severity severity, const std::string& text) {
  std::string clean = text;
  for (char& c : clean)  // text from the network never reaches the terminal as control bytes
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = ' ';
  std::function<double()> clock_s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    clock_s = clock_s_;
  }
  const double t_s = clock_s ? clock_s() : monotonic_s() - start_s_;  // outside the lock: the clock may take its own
  std::lock_guard<std::mutex> lock(mutex_);
  lines_.push_back({t_s, severity, std::move(clean)});
  while (lines_.size() > kCapacity) lines_.pop_front();
}

void MessageLog::add_lines(Severity severity, const std::string& text) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) add(severity, line);
    start = end + 1;
  }
}

std::vector<LogLine> MessageLog::lines() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {lines_.begin(), lines_.end()};
}

}  // namespace hitl::tui
