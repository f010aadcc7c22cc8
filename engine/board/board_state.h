// The board as it was before `hitl board install` changed it, written on the board (kStateFile)
// so that `hitl board restore` can put it back from any host:
//
//   # hitl board install: the board before it (hitl board restore reads this)
//   package voxl-hitl-vio-server -
//   package voxl-hitl-px4-scripts 0.0.9
//   service voxl-px4 enabled active
//   service voxl-hitl-vio-server disabled inactive
//   service voxl-vision-hub enabled active
//   file /etc/modalai/voxl-vision-hub.conf present
//   file /etc/modalai/voxl-hitl-vio-server.conf absent
//
// "-" is a package that was not installed. A present file's original is kept byte for byte as
// kBackupDir/<its name>.orig.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/board/board_survey.h"

namespace hitl::board {

struct BoardState {
  std::map<std::string, std::string> packages;  ///< package -> version, "" when not installed
  std::vector<ServiceState> services;
  std::map<std::string, bool> files_present;    ///< kVisionHubConf, kVioServerConf
};

/// The state a survey shows (what install records before it changes anything).
BoardState state_from_survey(const BoardSurvey& survey);
std::string format_board_state(const BoardState& state);
/// An Error of kind Input naming the line when the text is not such a record.
Expected<BoardState> parse_board_state(const std::string& text);

/// kBackupDir/<basename of path>.orig
std::string backup_path(const std::string& path);

}  // namespace hitl::board
