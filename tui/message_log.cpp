#include "tui/message_log.h"

#include "base/common/clock.h"
#include "base/mavlink/severity.h"

namespace hitl::tui {
namespace {

std::string clean(const std::string& text) {
  std::string out = text;
  for (char& c : out)  // text from the network never reaches the terminal as control bytes
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7F) c = ' ';
  return out;
}

}  // namespace

Severity severity_from_mavlink(uint8_t mav_severity) { return mavlink::severity_of(mav_severity); }

MessageLog::MessageLog(std::function<double()> wall_s)
    : wall_s_(wall_s ? std::move(wall_s) : std::function<double()>(monotonic_s)), start_s_(wall_s_()) {}

void MessageLog::set_clock(std::function<double()> clock_s) {
  std::lock_guard<std::mutex> lock(mutex_);
  clock_s_ = std::move(clock_s);
}

void MessageLog::push(Entry entry) {
  std::function<double()> clock_s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    clock_s = clock_s_;
  }
  const double wall_s = wall_s_();
  const double t_s = clock_s ? clock_s() : wall_s - start_s_;  // outside the lock: the clock may take its own
  entry.line.t_s = t_s;
  entry.wall_s = wall_s;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!entry.repeat_key.empty()) {
    for (auto it = entries_.rbegin(); it != entries_.rend(); ++it) {
      if (it->repeat_key != entry.repeat_key) continue;
      if (wall_s - it->wall_s <= kRepeatWindow_s) {
        entry.line.repeats = it->line.repeats + 1;
        entries_.erase(std::next(it).base());  // the earlier showing moves to the bottom
      }
      break;
    }
  }
  entries_.push_back(std::move(entry));
  while (entries_.size() > kCapacity) entries_.pop_front();
}

void MessageLog::add(Severity severity, const std::string& text) { push({{0, severity, clean(text)}, "", 0}); }

void MessageLog::add_outcome(Severity severity, const std::string& text) {
  push({{0, severity, clean(text)}, "", 0});
  std::lock_guard<std::mutex> lock(mutex_);
  outcome_ = entries_.back().line;
}

std::optional<LogLine> MessageLog::outcome() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return outcome_;
}

void MessageLog::add_statustext(Severity severity, const std::string& source, const std::string& text) {
  const std::string line = clean(text);
  push({{0, severity, line}, source + '\n' + line, 0});
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
  std::vector<LogLine> out;
  out.reserve(entries_.size());
  for (const auto& e : entries_) out.push_back(e.line);
  return out;
}

}  // namespace hitl::tui
