#include "engine/px4/px4_build.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>

namespace hitl::px4 {
namespace {

namespace fs = std::filesystem;

/// A line of a small generated header, or "" (the files are PX4's; at most 64 KiB read).
std::string first_match(const fs::path& file, const std::regex& pattern) {
  std::ifstream in(file);
  std::string line;
  std::size_t read = 0;
  std::smatch m;
  while (read < 64 * 1024 && std::getline(in, line)) {
    read += line.size() + 1;
    if (std::regex_search(line, m, pattern)) return m[1].str();
  }
  return "";
}

bool is_build(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "bin" / "px4", ec) && fs::is_directory(dir / "etc", ec);
}

}  // namespace

Expected<Px4Build> find_px4_build(const std::string& dir) {
  std::error_code ec;
  const fs::path given(dir);
  if (dir.empty()) return Error::input("no PX4 folder given");
  if (!fs::is_directory(given, ec)) return Error::input("'" + dir + "': no such folder");
  fs::path build = given;
  if (!is_build(build)) {
    if (is_build(given / "build" / "px4_sitl_default")) {
      build = given / "build" / "px4_sitl_default";
    } else if (fs::is_regular_file(given / "bin" / "px4", ec)) {
      return Error::input("'" + dir + "' is not a PX4 SITL build: no etc/ (PX4's ROMFS) beside bin/px4");
    } else if (fs::exists(given / "boards" / "px4" / "sitl", ec)) {
      return Error::input("'" + dir + "' is a PX4 tree with no SITL build (no build/px4_sitl_default/bin/px4): "
                          "build it with scripts/px4-sitl.sh " + dir);
    } else {
      return Error::input("'" + dir + "' is not a PX4 SITL build: no bin/px4, and not a PX4 tree with build/px4_sitl_default");
    }
  }
  Px4Build b;
  b.build_dir = fs::absolute(build, ec).lexically_normal().string();
  b.program = (fs::path(b.build_dir) / "bin" / "px4").string();
  b.etc_dir = (fs::path(b.build_dir) / "etc").string();
  if (::access(b.program.c_str(), X_OK) != 0) return Error::input("'" + b.program + "' is not executable");
  if (!fs::is_regular_file(fs::path(b.etc_dir) / "init.d-posix" / "rcS", ec))
    return Error::input("'" + b.etc_dir + "' has no init.d-posix/rcS: not a PX4 SITL build's ROMFS");
  static const std::regex kTag(R"re(#define\s+PX4_GIT_TAG_STR\s+"([^"]*)")re");
  b.version = first_match(fs::path(b.build_dir) / "src" / "lib" / "version" / "build_git_version.h", kTag);
  static const std::regex kNoLockstep(R"re(^(CONFIG_BOARD_NOLOCKSTEP)=y)re");
  b.lockstep = first_match(fs::path(b.build_dir) / "boardconfig", kNoLockstep).empty() &&
               build.filename().string().find("nolockstep") == std::string::npos;
  return b;
}

}  // namespace hitl::px4
