// What `hitl board` reads on the board before it plans anything (read-only commands): the HITL
// packages' versions, the services' states, the two configuration files, and the record a
// previous `hitl board install` left (board_state.h).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/board/board_shell.h"

namespace hitl::board {

struct ServiceState {
  std::string name;
  bool enabled = false;  ///< `systemctl is-enabled` said "enabled"
  bool active = false;   ///< `systemctl is-active` said "active"
};

struct BoardSurvey {
  std::map<std::string, std::string> installed;  ///< package -> version; "" when not installed
  std::vector<ServiceState> services;            ///< kRecordedServices, then kPx4HitlUnit
  std::optional<std::string> vision_hub_text;    ///< none: the board has no such file
  std::optional<std::string> vio_server_text;
  std::optional<std::string> state_text;         ///< a previous install's record (kStateFile)

  std::string version(const std::string& package) const;
  ServiceState service(const std::string& name) const;
};

/// The read-only commands the survey runs, in order (listed by --dry-run and docs/board.md).
std::vector<std::string> survey_commands();

/// Runs survey_commands() and reads their output.
Expected<BoardSurvey> survey_board(BoardShell& shell);

/// `dpkg-query -W` output ("name\tversion" lines; an empty version: known, not installed).
std::map<std::string, std::string> parse_dpkg_query(const std::string& output);
/// The service loop's output ("NAME ENABLED-WORD ACTIVE-WORD" lines).
std::vector<ServiceState> parse_service_states(const std::string& output);

}  // namespace hitl::board
