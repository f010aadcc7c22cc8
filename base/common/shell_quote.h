// A word as POSIX sh reads it back unchanged: inside single quotes, each ' written as '\''. For the
// command lines hitl writes for a shell: adb shell's, the completion scripts', batch scripts'.
#pragma once

#include <string>
#include <string_view>

namespace hitl {

inline std::string shell_quoted(std::string_view word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace hitl
