#include "engine/sensors/sensor_profiles.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "engine/model/config_json.h"

namespace hitl::sensors {
namespace {

using json = nlohmann::json;

constexpr std::string_view kImuPrefix = "imu-";

const EmbeddedProfile* find_imu_profile(std::string_view name) {
  for (const EmbeddedProfile& p : embedded_profiles()) {
    const std::string_view stem(p.file_stem);
    if (stem.starts_with(kImuPrefix) && stem.substr(kImuPrefix.size()) == name) return &p;
  }
  return nullptr;
}

Expected<json> profile_json(std::string_view name) {
  const EmbeddedProfile* p = find_imu_profile(name);
  if (p == nullptr) return Error::input("unknown IMU profile \"" + std::string(name) + "\" (known: " + imu_profile_list() + ")");
  // The files are the project's own: a parse error is a build defect, which the profile tests catch.
  return json::parse(p->text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
}

}  // namespace

std::vector<std::string> imu_profile_names() {
  std::vector<std::string> out;
  for (const EmbeddedProfile& p : embedded_profiles()) {
    const std::string_view stem(p.file_stem);
    if (stem.starts_with(kImuPrefix)) out.emplace_back(stem.substr(kImuPrefix.size()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string imu_profile_list() {
  std::string out;
  for (const std::string& n : imu_profile_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

Expected<ProfileInfo> imu_profile_info(std::string_view name) {
  auto root = profile_json(name);
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

Expected<model::VehicleConfig> apply_imu_profile(std::string_view name, const model::VehicleConfig& base) {
  auto root = profile_json(name);
  if (!root) return root.error();
  json wrapped;
  wrapped["sensors"]["imu"] = root->at("imu");
  return model::parse_vehicle_config(wrapped.dump(), "IMU profile " + std::string(name), base);
}

}  // namespace hitl::sensors
