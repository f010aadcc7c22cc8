#include "engine/board/board_state.h"

#include <sstream>

#include "engine/board/board_facts.h"

namespace hitl::board {

BoardState state_from_survey(const BoardSurvey& survey) {
  BoardState state;
  for (const char* p : kHitlPackages) state.packages[p] = survey.version(p);
  for (const char* s : kRecordedServices) state.services.push_back(survey.service(s));
  state.files_present[kVisionHubConf] = survey.vision_hub_text.has_value();
  state.files_present[kVioServerConf] = survey.vio_server_text.has_value();
  return state;
}

std::string format_board_state(const BoardState& state) {
  std::ostringstream out;
  out << "# hitl board install: the board before it (hitl board restore reads this)\n";
  for (const auto& [name, version] : state.packages) out << "package " << name << ' ' << (version.empty() ? "-" : version) << '\n';
  for (const auto& s : state.services)
    out << "service " << s.name << ' ' << (s.enabled ? "enabled" : "disabled") << ' ' << (s.active ? "active" : "inactive") << '\n';
  for (const auto& [path, present] : state.files_present) out << "file " << path << ' ' << (present ? "present" : "absent") << '\n';
  return out.str();
}

Expected<BoardState> parse_board_state(const std::string& text) {
  BoardState state;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string kind, a, b, c;
    words >> kind >> a >> b >> c;
    auto bad = [&] {
      return Error::input(std::string(kStateFile) + " line " + std::to_string(number) + ": '" + line +
                          "' is not a record hitl board install writes");
    };
    if (kind == "package" && !a.empty() && !b.empty() && c.empty()) {
      state.packages[a] = b == "-" ? "" : b;
    } else if (kind == "service" && (b == "enabled" || b == "disabled") && (c == "active" || c == "inactive")) {
      state.services.push_back({a, b == "enabled", c == "active"});
    } else if (kind == "file" && (b == "present" || b == "absent") && c.empty()) {
      state.files_present[a] = b == "present";
    } else {
      return bad();
    }
  }
  return state;
}

std::string backup_path(const std::string& path) {
  const auto slash = path.rfind('/');
  return std::string(kBackupDir) + "/" + (slash == std::string::npos ? path : path.substr(slash + 1)) + ".orig";
}

}  // namespace hitl::board
