#include "engine/vehicle/shell_status.h"

#include <cstdlib>
#include <sstream>

namespace hitl::vehicle {
namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

ShellStatus shell_status(const std::string& output) {
  ShellStatus status;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (starts_with(line, "Command '")) {
      const auto marker = line.find("' failed, returned ");
      if (marker == std::string::npos || !ends_with(line, ".")) continue;
      const std::string number = line.substr(marker + 19, line.size() - marker - 20);
      char* end = nullptr;
      const long code = std::strtol(number.c_str(), &end, 10);
      if (number.empty() || *end != '\0' || code == 0) continue;
      status = {static_cast<int>(code), line};
    } else if (starts_with(line, "Invalid command: ") ||
               (starts_with(line, "nsh: ") && ends_with(line, ": command not found"))) {
      status = {-1, line};
    }
  }
  return status;
}

}  // namespace hitl::vehicle
