// The PX4 build the `px4`-labelled tests fly (HITL_PX4_DIR), and what they say when there is none.
#pragma once

#include <cstdlib>
#include <string>

namespace hitl::test {

inline constexpr const char* kNoPx4Reason =
    "HITL_PX4_DIR is not set: these tests fly real PX4 SITL (build it with scripts/px4-sitl.sh TREE, then "
    "HITL_PX4_DIR=TREE ctest -L px4)";

/// HITL_PX4_DIR, or "" when it is unset or empty (the test then skips with kNoPx4Reason).
inline std::string px4_dir() {
  const char* dir = std::getenv("HITL_PX4_DIR");
  return dir == nullptr ? std::string() : std::string(dir);
}

}  // namespace hitl::test
