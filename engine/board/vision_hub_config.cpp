#include "engine/board/vision_hub_config.h"

#include <nlohmann/json.hpp>

#include <cctype>

#include "base/contract/board_ports.h"
#include "engine/board/board_facts.h"

namespace hitl::board {

bool VisionHubEdit::changes() const {
  for (const auto& k : keys)
    if (k.changes()) return true;
  return false;
}

const std::vector<std::pair<std::string, std::string>>& vision_hub_hitl_keys() {
  static const std::vector<std::pair<std::string, std::string>> keys{
      {"en_vio", "false"}, {"vio_pipe", "\"qvio\""}, {"en_hitl", "true"}, {"offboard_mode", "\"vfc\""}};
  return keys;
}

Expected<VisionHubEdit> edit_vision_hub_config(std::string_view original) {
  nlohmann::ordered_json config = nlohmann::ordered_json::object();
  bool blank = true;
  for (char c : original)
    if (!std::isspace(static_cast<unsigned char>(c))) blank = false;
  if (!blank) {
    try {
      config = nlohmann::ordered_json::parse(original);
    } catch (const nlohmann::json::parse_error& e) {
      return Error::input(std::string(kVisionHubConf) + " on the board is not valid JSON (" + e.what() +
                          "); fix or remove it, then run hitl board install again");
    }
    if (!config.is_object())
      return Error::input(std::string(kVisionHubConf) + " on the board is JSON but not an object ({...}); fix it, then run hitl board install again");
  }
  VisionHubEdit edit;
  for (const auto& [key, value] : vision_hub_hitl_keys()) {
    const auto wanted = nlohmann::ordered_json::parse(value);
    ConfigKeyChange change{key, config.contains(key) ? config[key].dump() : "absent", wanted.dump()};
    config[key] = wanted;
    edit.keys.push_back(std::move(change));
  }
  edit.text = config.dump(1, '\t') + "\n";
  return edit;
}

std::string vio_server_config_text() {
  nlohmann::ordered_json config = {{"receiver_ip", "0.0.0.0"}, {"receiver_port", kBoardVioPort}};
  return config.dump(1, '\t') + "\n";
}

}  // namespace hitl::board
