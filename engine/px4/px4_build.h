// A PX4 SITL build that hitl can start (hitl sim --px4 DIR): where its program and its ROMFS are,
// which version it is, and whether it runs in lockstep. DIR is a build folder (bin/px4 and etc/) or
// a PX4 tree whose build/px4_sitl_default holds one (scripts/px4-sitl.sh makes it).
#pragma once

#include <string>

#include "base/common/expected.h"

namespace hitl::px4 {

struct Px4Build {
  std::string build_dir;  ///< the build folder (absolute)
  std::string program;    ///< build_dir/bin/px4
  std::string etc_dir;    ///< build_dir/etc: the ROMFS with init.d-posix/rcS
  std::string version;    ///< "v1.16.0" (PX4_GIT_TAG_STR of the build); "" when the build does not say
  bool lockstep = true;   ///< false for a px4_sitl_nolockstep build (its board config says so)
};

/// The build at `dir`, or an input Error saying what is missing ("'DIR' is not a PX4 SITL build:
/// no bin/px4 (build it: scripts/px4-sitl.sh TREE)").
Expected<Px4Build> find_px4_build(const std::string& dir);

}  // namespace hitl::px4
