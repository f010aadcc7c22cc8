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

/// `sensors.imu.profile`: the profile applied to `base` (what the vehicle's reader reads over) and
/// the key taken out (the vehicle's reader does not know it).
void read_imu_profile(json& root, VehicleFile& out, model::VehicleConfig& base, std::vector<std::string>& errors) {
  if (!root.is_object()) return;
  auto sensors = root.find("sensors");
  if (sensors == root.end() || !sensors->is_object()) return;
  auto imu = sensors->find("imu");
  if (imu == sensors->end() || !imu->is_object()) return;
  auto profile = imu->find("profile");
  if (profile == imu->end()) return;
  if (!profile->is_string()) {
    errors.push_back("sensors.imu.profile: must be a string, one of: " + imu_profile_list() + " (got " + profile->dump() + ")");
  } else if (auto applied = apply_imu_profile(profile->get<std::string>(), base); !applied) {
    errors.push_back("sensors.imu.profile: " + applied.error().message);
  } else {
    base = std::move(*applied);
    out.imu_profile = profile->get<std::string>();
  }
  imu->erase(profile);
}

}  // namespace

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
  read_imu_profile(root, out, base, errors);
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
  root["sensors"]["imu"]["profile"] = file.imu_profile;  // every IMU key follows, so it reads back the same
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
