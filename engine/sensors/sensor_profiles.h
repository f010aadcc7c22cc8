// Sensor profiles: the figures of a real part from its datasheet, each a small JSON file in
// engine/sensors/profiles/<kind>-<name>.json (compiled in; its sources cited in its "sources" field),
// selected in the vehicle file by `sensors.<kind>.profile` for the kinds imu, baro, mag and gps
// ("generic", the default, is hitl's values before profiles). A profile sets some keys of
// `sensors.<kind>` (never rate_hz or the mount: those are the HIL link's and the vehicle's); keys the
// vehicle file sets itself apply over the profile.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"
#include "engine/model/vehicle_config.h"

namespace hitl::sensors {

/// One compiled-in profile file: its name without .json ("imu-icm-42688-p") and its text.
struct EmbeddedProfile {
  const char* file_stem;
  const char* text;
};
/// Every file of engine/sensors/profiles/, sorted by name (generated at build time).
const std::vector<EmbeddedProfile>& embedded_profiles();

/// What a profile says about itself (docs/engine.md's table).
struct ProfileInfo {
  std::string kind;  ///< "imu"
  std::string name;  ///< "icm-42688-p": the value of sensors.<kind>.profile
  std::string part;  ///< "TDK InvenSense ICM-42688-P"
  std::vector<std::pair<std::string, std::string>> sources;  ///< what -> where, as the file lists them
  std::vector<std::string> not_published;  ///< figures the maker's documents did not give (0 in the profile)
};

inline constexpr std::string_view kDefaultImuProfile = "generic";
inline constexpr std::string_view kDefaultProfile = "generic";
/// The kinds a profile can be of: each its file prefix, its section of `sensors` and its JSON key.
inline constexpr std::array<std::string_view, 4> kProfileKinds = {"imu", "baro", "mag", "gps"};

/// A kind's profiles' names, sorted ("baro": "generic", "icp-10100").
std::vector<std::string> profile_names(std::string_view kind);
/// "generic, icp-10100": the names for a message.
std::string profile_list(std::string_view kind);
Expected<ProfileInfo> profile_info(std::string_view kind, std::string_view name);
/// `base` with the profile `name` of `kind` applied (what the profile does not set kept). Unknown
/// name: an input error listing the known ones.
Expected<model::VehicleConfig> apply_profile(std::string_view kind, std::string_view name, const model::VehicleConfig& base);

/// The IMU profiles' names, sorted.
std::vector<std::string> imu_profile_names();
/// "generic, icm-42688-p": the names for a message.
std::string imu_profile_list();
Expected<ProfileInfo> imu_profile_info(std::string_view name);
/// `base` with the IMU profile `name` applied (rate and mount kept). Unknown name: an input error
/// listing the known ones.
Expected<model::VehicleConfig> apply_imu_profile(std::string_view name, const model::VehicleConfig& base);

}  // namespace hitl::sensors
