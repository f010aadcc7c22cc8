// hitl --json prints one object per line, the summary last: the tests read that last line.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace hitl::test {

/// The last non-empty line of `out`, parsed (empty JSON when there is none).
inline nlohmann::json last_json_line(const std::string& out) {
  const auto end = out.find_last_not_of('\n');
  if (end == std::string::npos) return {};
  const auto start = out.rfind('\n', end);
  return nlohmann::json::parse(out.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1));
}

}  // namespace hitl::test
