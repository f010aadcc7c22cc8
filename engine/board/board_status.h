// What `hitl board status` shows, decided from a survey and one look at PX4: the HITL packages
// against this build's version, the services, the two configuration files' relevant keys, the
// install record, PX4's HIL mode and dsp_hitl, the HITL parameter check, and whether all of it is
// ready for `hitl sim`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/board/board_survey.h"
#include "engine/board/px4_link.h"

namespace hitl::board {

struct PackageStatus {
  std::string name;
  std::string installed;   ///< "" when not installed
  std::string this_build;  ///< the hitl version that made the packages
  bool current() const { return !installed.empty() && installed == this_build; }
};

/// A configuration file's relevant keys: JSON text of each value, "absent" for a missing key.
struct ConfigKeys {
  bool present = false;
  std::string error;  ///< not JSON / not an object
  std::vector<std::pair<std::string, std::string>> keys;
};

struct BoardStatus {
  std::vector<PackageStatus> packages;
  std::vector<ServiceState> services;  ///< the recorded services and PX4's HITL unit
  ConfigKeys vision_hub;               ///< the spec's four keys
  bool vision_hub_hitl = false;        ///< they have the spec's values
  ConfigKeys vio_server;               ///< receiver_ip, receiver_port
  bool record = false;                 ///< an install record (restore has something to go back to)
  Px4Status px4;
  std::size_t params_wrong = 0;
  std::size_t params_absent = 0;
  std::vector<std::string> not_ready;  ///< why `hitl sim` would not work yet, one reason each; empty: ready
};

BoardStatus make_board_status(const BoardSurvey& survey, const std::string& this_build, Px4Status px4);

/// The named keys of a JSON object's text.
ConfigKeys config_keys(const std::optional<std::string>& text, const std::vector<std::string>& names);

}  // namespace hitl::board
