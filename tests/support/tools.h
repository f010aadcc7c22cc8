// Helpers for the ecosystem tests: find and run other programs (shells, groff, cmake, cpack,
// dpkg-deb), read and write files.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/process.h"

namespace hitl::test {

/// The full path of `name` on $PATH, or "" when it is not installed.
inline std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const auto candidate = std::filesystem::path(dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

/// Runs a program (looked up on $PATH when it has no '/') to completion.
inline RunResult run_program(std::vector<std::string> argv, std::chrono::milliseconds timeout = std::chrono::seconds(120)) {
  if (argv.front().find('/') == std::string::npos) {
    const auto full = find_program(argv.front());
    if (full.empty()) return {127, "", argv.front() + " is not installed"};
    argv.front() = full;
  }
  Process p(argv);
  const int code = p.wait(timeout);
  return {code, p.out(), p.err()};
}

inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void write_text(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

inline bool contains(const std::vector<std::string>& items, const std::string& item) {
  return std::find(items.begin(), items.end(), item) != items.end();
}

/// The source tree's path of a committed file.
inline std::string source_path(const std::string& relative) { return std::string(HITL_SOURCE_DIR) + "/" + relative; }

}  // namespace hitl::test
