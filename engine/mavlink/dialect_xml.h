// Loads MAVLink message definitions from XML at run time (with their <include>s), so
// hitl can name, checksum and print messages it does not compile in.
#pragma once

#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/mavlink/message_set.h"

namespace hitl::mavlink {

struct DialectInfo {
  std::vector<std::string> files;  ///< every file read, includes first
  std::size_t messages = 0;        ///< messages defined across them
};

/// Adds every message of `path` and the files it includes to `set` (later definitions win).
Expected<DialectInfo> load_dialect(const std::string& path, MessageSet& set);

/// Name of the environment variable holding dialect files (':'-separated) to load by default.
inline constexpr const char* kDialectEnvVar = "HITL_MAVLINK_DIALECT";

}  // namespace hitl::mavlink
