#include "engine/sensors/sensor_profiles.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "engine/model/config_json.h"

namespace hitl::sensors {
namespace {

using json = nlohmann::json;

/// "IMU", "barometer": a kind in an error message.
std::string kind_words(std::string_view kind) {
  if (kind == "imu") return "IMU";
  if (kind == "baro") return "barometer";
  if (kind == "mag") return "magnetometer";
  if (kind == "gps") return "GPS";
  return std::string(kind);
}

const EmbeddedProfile* find_profile(std::string_view kind, std::string_view name) {
  const std::string prefix = std::string(kind) + "-";
  for (const EmbeddedProfile& p : embedded_profiles()) {
    const std::string_view stem(p.file_stem);
    if (stem.starts_with(prefix) && stem.substr(prefix.size()) == name) return &p;
  }
  return nullptr;
}

Expected<json> profile_json(std::string_view kind, std::string_view name) {
  const EmbeddedProfile* p = find_profile(kind, name);
  if (p == nullptr)
    return Error::input("unknown " + kind_words(kind) + " profile \"" + std::string(name) + "\" (known: " + profile_list(kind) + ")");
  // The files are the project's own: a parse error is a build defect, which the profile tests catch.
  return json::parse(p->text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
}

}  // namespace

std::vector<std::string> profile_names(std::string_view kind) {
  const std::string prefix = std::string(kind) + "-";
  std::vector<std::string> out;
  for (const EmbeddedProfile& p : embedded_profiles()) {
    const std::string_view stem(p.file_stem);
    if (stem.starts_with(prefix)) out.emplace_back(stem.substr(prefix.size()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string profile_list(std::string_view kind) {
  std::string out;
  for (const std::string& n : profile_names(kind)) out += (out.empty() ? "" : ", ") + n;
  return out;
}

Expected<ProfileInfo> profile_info(std::string_view kind, std::string_view name) {
  auto root = profile_json(kind, name);
  if (!root) return root.error();
  ProfileInfo info;
  // Every profile has these fields (the profile tests read each file).
  info.kind = root->at("kind").get<std::string>();
  info.name = root->at("name").get<std::string>();
  info.part = root->at("part").get<std::string>();
  const json& sources = root->at("sources");
  for (auto it = sources.begin(); it != sources.end(); ++it) info.sources.emplace_back(it.key(), it.value().get<std::string>());
  if (root->contains("not_published"))
    for (const json& n : root->at("not_published")) info.not_published.push_back(n.get<std::string>());
  return info;
}

Expected<model::VehicleConfig> apply_profile(std::string_view kind, std::string_view name, const model::VehicleConfig& base) {
  auto root = profile_json(kind, name);
  if (!root) return root.error();
  json wrapped;
  wrapped["sensors"][std::string(kind)] = root->at(std::string(kind));
  return model::parse_vehicle_config(wrapped.dump(), kind_words(kind) + " profile " + std::string(name), base);
}

std::vector<std::string> imu_profile_names() { return profile_names("imu"); }
std::string imu_profile_list() { return profile_list("imu"); }
Expected<ProfileInfo> imu_profile_info(std::string_view name) { return profile_info("imu", name); }
Expected<model::VehicleConfig> apply_imu_profile(std::string_view name, const model::VehicleConfig& base) {
  return apply_profile("imu", name, base);
}

}  // namespace hitl::sensors
