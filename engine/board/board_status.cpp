#include "engine/board/board_status.h"

#include <nlohmann/json.hpp>

#include "engine/board/board_facts.h"
#include "engine/board/vision_hub_config.h"

namespace hitl::board {

ConfigKeys config_keys(const std::optional<std::string>& text, const std::vector<std::string>& names) {
  ConfigKeys c;
  if (!text) return c;
  c.present = true;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(*text);
  } catch (const nlohmann::json::parse_error&) {
    c.error = "not valid JSON";
    return c;
  }
  if (!j.is_object()) {
    c.error = "not a JSON object";
    return c;
  }
  for (const auto& n : names) c.keys.emplace_back(n, j.contains(n) ? j[n].dump() : "absent");
  return c;
}

BoardStatus make_board_status(const BoardSurvey& survey, const std::string& this_build, Px4Status px4) {
  BoardStatus s;
  for (const char* p : kHitlPackages) {
    s.packages.push_back({p, survey.version(p), this_build});
    if (!s.packages.back().current())
      s.not_ready.push_back(std::string(p) + (s.packages.back().installed.empty() ? " is not installed" : " is not this build's version") +
                            ": hitl board install");
  }
  for (const char* name : kRecordedServices) s.services.push_back(survey.service(name));
  s.services.push_back(survey.service(kPx4HitlUnit));

  std::vector<std::string> hub_names;
  for (const auto& [k, v] : vision_hub_hitl_keys()) hub_names.push_back(k);
  s.vision_hub = config_keys(survey.vision_hub_text, hub_names);
  s.vision_hub_hitl = s.vision_hub.present && s.vision_hub.error.empty();
  for (std::size_t i = 0; s.vision_hub_hitl && i < s.vision_hub.keys.size(); ++i)
    s.vision_hub_hitl = nlohmann::json::parse(s.vision_hub.keys[i].second == "absent" ? "null" : s.vision_hub.keys[i].second) ==
                        nlohmann::json::parse(vision_hub_hitl_keys()[i].second);
  if (!s.vision_hub_hitl) s.not_ready.push_back(std::string(kVisionHubConf) + " lacks the spec's HITL keys: hitl board install");
  s.vio_server = config_keys(survey.vio_server_text, {"receiver_ip", "receiver_port"});
  s.record = survey.state_text.has_value();

  for (const char* name : {kPx4HitlUnit, kVioServerService, kVisionHubService})
    if (!survey.service(name).active) s.not_ready.push_back(std::string(name) + " is not running: hitl board start");
  s.px4 = std::move(px4);
  if (!s.px4.heartbeat) s.not_ready.push_back("no HEARTBEAT from PX4: " + s.px4.link_error);
  else if (!s.px4.hil_mode) s.not_ready.push_back("PX4 is not in HIL mode (HEARTBEAT lacks MAV_MODE_FLAG_HIL_ENABLED): hitl board start");
  if (s.px4.heartbeat && s.px4.dsp_hitl_running != true) s.not_ready.push_back("dsp_hitl is not running: hitl board start");
  for (const auto& row : s.px4.params) {
    if (row.absent) ++s.params_absent;
    else if (!row.ok) ++s.params_wrong;
  }
  if (s.params_wrong > 0) s.not_ready.push_back(std::to_string(s.params_wrong) + " HITL parameter(s) differ: hitl board start sets them");
  return s;
}

}  // namespace hitl::board
