// The whole vehicle file: the vehicle (engine/model, config_json.h) and the sensor units' sections
// `sensors.<name>` (units.h), each unit reading its own keys with its fields(). Read over the
// compiled-in defaults like the rest of the file; every error names its key, e.g.
// `vehicle.json: sensors.rangefinder.rate_hz: must be in [0.1, 10000] (got 0)`. `sensors.<kind>.profile`
// (imu, baro, mag, gps) picks that sensor's datasheet profile (sensor_profiles.h), which the file's
// other keys of that sensor override.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"
#include "engine/model/vehicle_config.h"
#include "engine/sensors/sensor_profiles.h"
#include "engine/sensors/unit_set.h"

namespace hitl::sensors {

struct VehicleFile {
  model::VehicleConfig vehicle;
  /// `sensors.<kind>.profile` (sensor_profiles.h): the profile each sensor's keys were read over.
  std::string imu_profile{kDefaultProfile};
  std::string baro_profile{kDefaultProfile};
  std::string mag_profile{kDefaultProfile};
  std::string gps_profile{kDefaultProfile};
  UnitConfigs units;  ///< every unit's defaults when the file has no section for it (off)
};

/// The profile of `kind` ("imu", "baro", "mag", "gps") the file selected.
const std::string& profile_of(const VehicleFile& file, std::string_view kind);
std::string& profile_of(VehicleFile& file, std::string_view kind);

/// The x500 with every unit at its defaults.
VehicleFile default_vehicle_file();
Expected<VehicleFile> parse_vehicle_file(std::string_view json_text, std::string_view source_name);
/// Reads a file (bounded, as the other config files); errors are prefixed by the path as given.
Expected<VehicleFile> load_vehicle_file(const std::filesystem::path& file);
/// The complete file, the units' sections included.
std::string to_json_text(const VehicleFile& file);
/// "sensors.rangefinder.enabled", ...: every unit's keys (tests/engine/sensors checks docs/engine.md lists them).
std::vector<std::string> unit_keys();

}  // namespace hitl::sensors
