// How deep a JSON text nests, checked before it is parsed: a file nested tens of thousands of
// arrays deep parses (nlohmann's parser keeps its own stack) but anything that walks the value
// recursively afterwards, dump() in an error message first, overflows the stack. Every JSON file
// hitl reads is a few levels deep; kMaxJsonDepth is far above any of them.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "base/common/expected.h"

namespace hitl {

inline constexpr std::size_t kMaxJsonDepth = 32;

/// Ok, or an Input error "WHAT: is nested deeper than 32 levels (at byte N)" when `text` opens more
/// than `max_depth` arrays or objects inside each other. Brackets inside strings do not count; the
/// rest of the syntax is the parser's to check.
inline Status check_json_depth(std::string_view text, const std::string& what, std::size_t max_depth = kMaxJsonDepth) {
  std::size_t depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        return Error::input(what + ": is nested deeper than " + std::to_string(max_depth) + " levels (at byte " + std::to_string(i) + ")");
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return Ok{};
}

}  // namespace hitl
