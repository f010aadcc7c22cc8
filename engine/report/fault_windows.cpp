#include "engine/report/fault_windows.h"

#include <algorithm>
#include <cstdlib>

#include "engine/faults/fault_spec.h"

namespace hitl::report {
namespace {

std::optional<double> number_at(std::string_view text, std::size_t& at) {
  const std::string digits(text.substr(at, std::min<std::size_t>(text.size() - at, 32)));
  char* end = nullptr;
  const double v = std::strtod(digits.c_str(), &end);
  if (end == digits.c_str()) return std::nullopt;
  at += static_cast<std::size_t>(end - digits.c_str());
  return v;
}

bool take(std::string_view text, std::size_t& at, std::string_view word) {
  if (text.substr(at, word.size()) != word) return false;
  at += word.size();
  return true;
}

}  // namespace

std::optional<FaultChangeText> parse_fault_change(std::string_view text) {
  std::size_t at = 0;
  FaultChangeText c;
  if (!take(text, at, "t=")) return std::nullopt;
  const auto t_s = number_at(text, at);
  if (!t_s || !(*t_s >= 0 && *t_s <= kMaxFaultTime_s) || !take(text, at, " s fault ")) return std::nullopt;
  c.t_s = *t_s;
  const auto space = text.find(' ', at);
  if (space == std::string_view::npos || space == at) return std::nullopt;
  c.label = std::string(text.substr(at, space - at));
  if (c.label.front() == ':') return std::nullopt;  // arguments without a fault's name
  at = space;
  if (take(text, at, " ended")) return at == text.size() ? std::optional(c) : std::nullopt;
  if (!take(text, at, " started")) return std::nullopt;  // "refused: ..." is no window
  c.started = true;
  if (at == text.size()) return c;
  if (!take(text, at, " (")) return std::nullopt;
  c.duration_s = number_at(text, at);
  if (!c.duration_s || !(*c.duration_s >= 0 && *c.duration_s <= kMaxFaultTime_s) || !take(text, at, " s)") || at != text.size())
    return std::nullopt;
  return c;
}

std::vector<FaultWindow> fault_windows(const std::vector<LogEvent>& events, bool simulated_time, const std::string& simulator_source) {
  std::vector<FaultWindow> out;
  for (const auto& e : events) {
    if (e.source != simulator_source) continue;
    const auto c = parse_fault_change(e.text);
    if (!c) continue;
    const double t_s = simulated_time ? c->t_s : e.t_s;
    if (c->started) {
      const auto colon = c->label.find(':');
      out.push_back({c->label.substr(0, colon), colon == std::string::npos ? "" : c->label.substr(colon + 1), t_s, std::nullopt,
                     c->duration_s});
      continue;
    }
    for (auto& w : out)
      if (!w.end_s && w.label() == c->label) {
        w.end_s = t_s;
        break;
      }
  }
  return out;
}

std::string named_fault_args(const std::string& label) {
  const auto colon = label.find(':');
  if (colon == std::string::npos) return "";
  const std::string name = label.substr(0, colon), args = label.substr(colon + 1);
  const faults::FaultInfo* info = faults::find_fault(name);
  std::string out;
  std::size_t k = 0, at = 0;
  while (at <= args.size()) {
    auto comma = args.find(',', at);
    if (comma == std::string::npos) comma = args.size();
    if (!out.empty()) out += ", ";
    if (info != nullptr && k < info->args.size()) out += std::string(info->args[k].name) + " ";
    out += args.substr(at, comma - at);
    ++k;
    at = comma + 1;
  }
  return out;
}

}  // namespace hitl::report
