// Reading a whole file that came from outside, with a size cap: /dev/zero, a FIFO that never
// ends or a multi-gigabyte mistake gives a named error after reading at most the cap, instead of
// growing until the machine runs out of memory.
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstring>
#include <fstream>
#include <string>

#include "base/common/expected.h"

namespace hitl {

/// Caps for the kinds of files hitl reads whole (each far above any real file of the kind).
inline constexpr std::size_t kMaxConfigFileBytes = 1 << 20;       ///< TOML, JSON configuration, parameters: 1 MiB
inline constexpr std::size_t kMaxTrajectoryFileBytes = 16 << 20;  ///< trajectories: 16 MiB
inline constexpr std::size_t kMaxDialectFileBytes = 16 << 20;     ///< MAVLink XML: 16 MiB

/// "1 MiB", "16 MiB", "512 KiB", "100 bytes".
inline std::string byte_size_text(std::size_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= 1024 && bytes % 1024 == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}

/// The contents of `path` (`what` names it in errors: "trajectory", "parameter file", ...), or an
/// Input error when it cannot be opened, is a directory, or holds more than `max_bytes`.
inline Expected<std::string> read_bounded_file(const std::string& path, const std::string& what, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error::input("cannot read " + what + " '" + path + "': " + std::strerror(errno));
  std::string text;
  char chunk[65536];
  while (in) {
    in.read(chunk, sizeof chunk);
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes)
      return Error::input(what + " '" + path + "' is larger than " + byte_size_text(max_bytes) + ", the limit for a " + what +
                          " (an endless file such as /dev/zero?)");
  }
  if (in.bad()) return Error::input("cannot read " + what + " '" + path + "': " + std::strerror(errno));
  return text;
}

}  // namespace hitl
