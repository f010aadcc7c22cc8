// Sensor profiles: the figures of a real part from its datasheet, each a small JSON file in
// engine/sensors/profiles/ (compiled in; its sources cited in its "sources" field), selected in the
// vehicle file by `sensors.imu.profile` ("generic", the default, or "icm-42688-p"). A profile sets
// the IMU's ranges, resolution and noise (the keys of `sensors.imu` except rate_hz and the mount);
// keys the vehicle file sets itself apply over the profile.
#pragma once

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

/// The IMU profiles' names, sorted.
std::vector<std::string> imu_profile_names();
/// "generic, icm-42688-p": the names for a message.
std::string imu_profile_list();
Expected<ProfileInfo> imu_profile_info(std::string_view name);
/// `base` with the IMU profile `name` applied (rate and mount kept). Unknown name: an input error
/// listing the known ones.
Expected<model::VehicleConfig> apply_imu_profile(std::string_view name, const model::VehicleConfig& base);

}  // namespace hitl::sensors
