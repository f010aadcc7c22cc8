#include "engine/vehicle/param_notes.h"

#include <sstream>

namespace hitl::vehicle {

// Generated at build time from base/contract/hitl-defaults.params (see CMakeLists.txt).
extern const char* const kHitlDefaultParamsText;

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

}  // namespace

std::vector<AbsentParamNote> parse_absent_notes(std::string_view text) {
  std::vector<AbsentParamNote> out;
  std::istringstream in{std::string(text)};
  const std::string marker = "#absent ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(marker, 0) != 0) continue;
    const std::string rest = line.substr(marker.size());
    const auto bar1 = rest.find('|');
    const auto bar2 = bar1 == std::string::npos ? std::string::npos : rest.find('|', bar1 + 1);
    if (bar2 == std::string::npos) continue;
    AbsentParamNote note{trim(rest.substr(0, bar1)), trim(rest.substr(bar1 + 1, bar2 - bar1 - 1)), trim(rest.substr(bar2 + 1))};
    if (note.name.empty() || note.firmware.empty()) continue;
    out.push_back(std::move(note));
  }
  return out;
}

const std::vector<AbsentParamNote>& hitl_absent_notes() {
  static const std::vector<AbsentParamNote> notes = parse_absent_notes(kHitlDefaultParamsText);
  return notes;
}

const AbsentParamNote* find_absent_note(const std::string& name) {
  for (const auto& n : hitl_absent_notes())
    if (n.name == name) return &n;
  return nullptr;
}

}  // namespace hitl::vehicle
