// Mistakes get help, as git and cargo give: "did you mean" for a misspelt command or option, range
// errors in plain numbers, and a config file's error naming the file, the line, and TOML.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace hitl::cli {

/// The candidate closest to `word` when it is close enough to be a slip of the keyboard.
std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& candidates);

/// A better message for `error` (parsing `args`, argv without the program name), or "" when CLI11's
/// own says it well enough. `config_file`: --config's value, when one was given.
std::string explain_parse_error(CLI::App& app, const CLI::ParseError& error, const std::vector<std::string>& args,
                                const std::string& config_file);

}  // namespace hitl::cli
