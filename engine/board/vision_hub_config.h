// voxl-vision-hub's configuration for HITL (the spec's step 7): the JSON edited, never replaced.
// The spec's keys are set, every other key is kept with its value and in its order
// (nlohmann::ordered_json); the text is written back tab-indented, as ModalAI's tools write it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"

namespace hitl::board {

/// One key the edit sets: its name, the value it wants (JSON text) and what the file had
/// ("absent" when it had no such key).
struct ConfigKeyChange {
  std::string key;
  std::string from;  ///< JSON text, or "absent"
  std::string to;    ///< JSON text
  bool changes() const { return from != to; }
};

struct VisionHubEdit {
  std::string text;                       ///< the whole new file
  std::vector<ConfigKeyChange> keys;      ///< the spec's keys, in the spec's order
  bool changes() const;                   ///< any key differs
};

/// The spec's keys and values: en_vio false, vio_pipe "qvio", en_hitl true, offboard_mode "vfc".
const std::vector<std::pair<std::string, std::string>>& vision_hub_hitl_keys();

/// Edits `original` (the file's text; empty when the board has no such file: a new object).
/// An Error of kind Input, naming the file and the problem, when it is not a JSON object.
Expected<VisionHubEdit> edit_vision_hub_config(std::string_view original);

/// voxl-hitl-vio-server's configuration as the spec's step 7 writes it.
std::string vio_server_config_text();

}  // namespace hitl::board
