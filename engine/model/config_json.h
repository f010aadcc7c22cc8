// The vehicle and world config files (JSON): read, merged over a base (the compiled-in x500 and
// default world unless given), validated; and written back. Every key, default and unit is listed
// in docs/engine.md. Errors name the file and the key:
//   "vehicle.json: rotors[2].time_constant_up_s: must be > 0 (got -1)"
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "base/common/expected.h"
#include "engine/model/vehicle_config.h"
#include "engine/model/world_config.h"

namespace hitl::model {

/// Reads `json_text` (comments allowed) over `base`: keys present replace base values, keys absent
/// keep them; `rotors` must list four objects, each merged over the base rotor of the same index.
/// Unknown keys, wrong types and out-of-range values are errors, all of them reported (one a line),
/// each prefixed by `source_name`.
Expected<VehicleConfig> parse_vehicle_config(std::string_view json_text, std::string_view source_name,
                                             const VehicleConfig& base);
/// As above over x500_vehicle_config().
Expected<VehicleConfig> parse_vehicle_config(std::string_view json_text, std::string_view source_name = "vehicle config");
/// Reads a file over x500_vehicle_config(); errors are prefixed by the path as given.
Expected<VehicleConfig> load_vehicle_config(const std::filesystem::path& file);

Expected<WorldConfig> parse_world_config(std::string_view json_text, std::string_view source_name,
                                         const WorldConfig& base);
Expected<WorldConfig> parse_world_config(std::string_view json_text, std::string_view source_name = "world config");
Expected<WorldConfig> load_world_config(const std::filesystem::path& file);

/// The whole config as a JSON document (2-space indent) that the parsers read back to the same values.
std::string to_json_text(const VehicleConfig& config);
std::string to_json_text(const WorldConfig& config);

/// The range checks of the parsers, for configs built in code.
Status validate(const VehicleConfig& config);
Status validate(const WorldConfig& config);

}  // namespace hitl::model
