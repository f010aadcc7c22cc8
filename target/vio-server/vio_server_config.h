// voxl-hitl-vio-server's configuration: /etc/modalai/voxl-hitl-vio-server.conf, JSON with the
// spec's keys. The defaults are the packaged voxl-hitl-vio-server.conf beside this file, compiled
// in (the one copy of their values); a missing file is created from it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "base/common/expected.h"

namespace hitl::vio {

inline constexpr const char* kDefaultConfigPath = "/etc/modalai/voxl-hitl-vio-server.conf";

struct VioServerConfig {
  std::string receiver_ip;     ///< "receiver_ip": bind address of the UDP socket (0.0.0.0: all interfaces)
  uint16_t receiver_port = 0;  ///< "receiver_port": UDP port ODOMETRY arrives on
};

/// The text of the packaged default file.
std::string_view default_config_text();
/// The defaults, parsed from default_config_text().
VioServerConfig default_config();

/// Parses the JSON of a config file; keys it lacks keep their default. Errors name `source` and the
/// key: not JSON, not an object, an unknown key, a value of the wrong type or out of range.
Expected<VioServerConfig> parse_config(std::string_view text, std::string_view source);

struct LoadedConfig {
  VioServerConfig config;
  bool created = false;  ///< the file did not exist and was written with the defaults
};
/// Reads `path`; when it does not exist, creates it (and its directory) with the defaults.
Expected<LoadedConfig> load_or_create_config(const std::string& path);

}  // namespace hitl::vio
