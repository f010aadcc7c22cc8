#include "engine/sensors/vehicle_file.h"

#include <nlohmann/json.hpp>

#include "base/common/bounded_read.h"
#include "engine/model/config_fields.h"
#include "engine/model/config_json.h"
#include "engine/model/x500_defaults.h"

namespace hitl::sensors {
namespace {

using json = nlohmann::json;

std::string unit_path(std::string_view name) { return "sensors." + std::string(name); }

/// `sensors.<kind>.profile`: the profile applied to `base` (what the vehicle's reader reads over)
/// and the key taken out (the vehicle's reader does not know it).
void read_profile(std::string_view kind, json& root, VehicleFile& out, model::VehicleConfig& base,
                  std::vector<std::string>& errors) {
  if (!root.is_object()) return;
  auto sensors = root.find("sensors");
  if (sensors == root.end() || !sensors->is_object()) return;
  auto section = sensors->find(std::string(kind));
  if (section == sensors->end() || !section->is_object()) return;
  auto profile = section->find("profile");
  if (profile == section->end()) return;
  const std::string key = "sensors." + std::string(kind) + ".profile";
  if (!profile->is_string()) {
    errors.push_back(key + ": must be a string, one of: " + profile_list(kind) + " (got " + profile->dump() + ")");
  } else if (auto applied = apply_profile(kind, profile->get<std::string>(), base); !applied) {
    errors.push_back(key + ": " + applied.error().message);
  } else {
    base = std::move(*applied);
    profile_of(out, kind) = profile->get<std::string>();
  }
  section->erase(profile);
}

}  // namespace

std::string& profile_of(VehicleFile& file, std::string_view kind) {
  if (kind == "baro") return file.baro_profile;
  if (kind == "mag") return file.mag_profile;
  if (kind == "gps") return file.gps_profile;
  return file.imu_profile;
}
const std::string& profile_of(const VehicleFile& file, std::string_view kind) {
  return profile_of(const_cast<VehicleFile&>(file), kind);  // the same field, only read
}

VehicleFile default_vehicle_file() {
  VehicleFile file;
  file.vehicle = model::x500_vehicle_config();
  return file;
}

Expected<VehicleFile> parse_vehicle_file(std::string_view json_text, std::string_view source_name) {
  const std::string source(source_name);
  json root;
  try {
    root = json::parse(json_text.begin(), json_text.end(), nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception&) {
    // Not JSON: the vehicle's reader says so, in the words it uses for every config file.
    auto vehicle = model::parse_vehicle_config(json_text, source_name);
    if (!vehicle) return vehicle.error();
    return Error::input(source + ": not valid JSON");
  }
  VehicleFile out = default_vehicle_file();
  std::vector<std::string> errors;
  model::VehicleConfig base = out.vehicle;
  for (std::string_view kind : kProfileKinds) read_profile(kind, root, out, base, errors);
  if (root.is_object() && root.contains("sensors") && root.at("sensors").is_object()) {
    json& sensors = root.at("sensors");
    for_each_unit([&](auto i) {
      using U = UnitAt<decltype(i)::value>;
      auto it = sensors.find(U::kName);
      if (it == sensors.end()) return;
      auto& config = std::get<decltype(i)::value>(out.units);
      if (!it->is_object()) {
        errors.push_back(unit_path(U::kName) + ": must be an object (got " + it->dump() + ")");
      } else {
        model::config_fields::Reader reader(*it, unit_path(U::kName), errors);
        U::fields(reader, config);
        reader.finish();
        if (const std::string problem = U::check(config); !problem.empty() && errors.empty())
          errors.push_back(unit_path(U::kName) + ": " + problem);
      }
      sensors.erase(it);  // the vehicle's reader does not know the units
    });
  }
  auto vehicle = model::parse_vehicle_config(root.dump(), source_name, base);
  if (!vehicle && errors.empty()) return vehicle.error();
  if (!errors.empty()) {
    std::string message = vehicle ? "" : vehicle.error().message;
    for (const std::string& e : errors) message += (message.empty() ? "" : "\n") + source + ": " + e;
    return Error::input(message);
  }
  out.vehicle = std::move(vehicle.value());
  return out;
}

Expected<VehicleFile> load_vehicle_file(const std::filesystem::path& file) {
  auto text = read_bounded_file(file.string(), "vehicle file", kMaxConfigFileBytes);
  if (!text) return text.error();
  return parse_vehicle_file(*text, file.string());
}

std::string to_json_text(const VehicleFile& file) {
  json root = json::parse(model::to_json_text(file.vehicle));
  // Every key of each sensor follows its profile, so the file reads back the same.
  for (std::string_view kind : kProfileKinds) root["sensors"][std::string(kind)]["profile"] = profile_of(file, kind);
  for_each_unit([&](auto i) {
    using U = UnitAt<decltype(i)::value>;
    json section;
    model::config_fields::Writer writer(section);
    U::fields(writer, const_cast<typename U::Config&>(std::get<decltype(i)::value>(file.units)));  // the Writer only reads
    root["sensors"][U::kName] = section;
  });
  return root.dump(2);
}

std::vector<std::string> unit_keys() {
  std::vector<std::string> out;
  for_each_unit([&](auto i) {
    using U = UnitAt<decltype(i)::value>;
    KeyNames names;
    typename U::Config config;
    U::fields(names, config);
    for (const auto& k : names.keys) out.push_back(unit_path(U::kName) + "." + k);
  });
  return out;
}

}  // namespace hitl::sensors
