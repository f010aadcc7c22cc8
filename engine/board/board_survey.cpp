#include "engine/board/board_survey.h"

#include <sstream>

#include "engine/board/board_facts.h"

namespace hitl::board {
namespace {

/// Exit code of the file reads when the file does not exist.
constexpr int kAbsentExit = 3;
/// A configuration file or the record larger than this is not one: the board sends one byte more
/// at most (head -c), so a huge file never fills the host's memory.
constexpr std::size_t kMaxFileBytes = 1 << 20;

std::string read_file_command(const std::string& path) {
  return "test -e " + path + " || exit 3; head -c " + std::to_string(kMaxFileBytes + 1) + " " + path;
}

std::string services_command() {
  std::string list;
  for (const char* s : kRecordedServices) list += std::string(s) + " ";
  list += kPx4HitlUnit;
  return "for s in " + list + "; do echo \"$s $(systemctl is-enabled $s 2>/dev/null) $(systemctl is-active $s 2>/dev/null)\"; done";
}

std::string packages_command() {
  std::string cmd = "dpkg-query -W";
  for (const char* p : kHitlPackages) cmd += std::string(" ") + p;
  return cmd + " 2>/dev/null";
}

Expected<std::optional<std::string>> read_file(BoardShell& shell, const std::string& path) {
  auto out = shell.run(read_file_command(path));
  if (!out) return out.error();
  if (out->exit_code == kAbsentExit) return std::optional<std::string>{};
  if (out->exit_code != 0) return Error::failed("cannot read " + path + " on the board (exit " + std::to_string(out->exit_code) + "): " + out->err);
  if (out->out.size() > kMaxFileBytes)
    return Error::input(path + " on the board is over " + std::to_string(kMaxFileBytes / 1024) + " KiB: not a configuration file hitl edits");
  return std::optional<std::string>{out->out};
}

}  // namespace

std::string BoardSurvey::version(const std::string& package) const {
  auto it = installed.find(package);
  return it == installed.end() ? std::string() : it->second;
}

ServiceState BoardSurvey::service(const std::string& name) const {
  for (const auto& s : services)
    if (s.name == name) return s;
  return {name, false, false};
}

std::vector<std::string> survey_commands() {
  return {packages_command(), services_command(), read_file_command(kVisionHubConf), read_file_command(kVioServerConf),
          read_file_command(kStateFile)};
}

std::map<std::string, std::string> parse_dpkg_query(const std::string& output) {
  std::map<std::string, std::string> installed;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto tab = line.find('\t');
    if (tab == std::string::npos || tab == 0) continue;
    installed[line.substr(0, tab)] = line.substr(tab + 1);
  }
  return installed;
}

std::vector<ServiceState> parse_service_states(const std::string& output) {
  std::vector<ServiceState> states;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    ServiceState s;
    std::string enabled, active;
    if (!(words >> s.name)) continue;
    words >> enabled >> active;
    // An unknown unit prints nothing for is-enabled and "inactive" (or nothing) for is-active.
    if (active.empty() && (enabled == "active" || enabled == "inactive" || enabled == "failed")) std::swap(enabled, active);
    s.enabled = enabled == "enabled";
    s.active = active == "active";
    states.push_back(s);
  }
  return states;
}

Expected<BoardSurvey> survey_board(BoardShell& shell) {
  BoardSurvey survey;
  auto packages = shell.run(packages_command());
  if (!packages) return packages.error();
  survey.installed = parse_dpkg_query(packages->out);
  auto services = shell.run(services_command());
  if (!services) return services.error();
  survey.services = parse_service_states(services->out);
  auto hub = read_file(shell, kVisionHubConf);
  if (!hub) return hub.error();
  survey.vision_hub_text = *hub;
  auto vio = read_file(shell, kVioServerConf);
  if (!vio) return vio.error();
  survey.vio_server_text = *vio;
  auto state = read_file(shell, kStateFile);
  if (!state) return state.error();
  survey.state_text = *state;
  return survey;
}

}  // namespace hitl::board
