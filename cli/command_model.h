// The hitl command line as plain data, read from the CLI11 App tree that parses it. The shell
// completions, the man page and the config reference are all generated from this one model, so
// they cannot drift from what `hitl` accepts.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace hitl::cli {

/// What an option's (or positional's) value is, for completing and documenting it.
enum class ValueKind {
  None,         ///< a flag: no value
  Text,         ///< anything (a number, an address): nothing to offer
  Choice,       ///< one of `choices` (CLI::IsMember, CLI::CheckedTransformer, BOOLEAN)
  File,         ///< a file path, `file_pattern` ("*.json") when the type says FILE.json
  Directory,    ///< a directory
  MessageList,  ///< MAVLink message names, comma-separated (value_type::kMessageList)
  MessageRates, ///< NAME=HZ pairs, comma-separated (value_type::kMessageRateList)
  FaultSpec     ///< a fault, its name from the catalogue first (value_type::kFaultSpec)
};

struct OptionModel {
  std::vector<std::string> long_names;   ///< without "--", in declaration order
  std::vector<std::string> short_names;  ///< without "-"
  std::string positional;                ///< the positional's name (e.g. FILE); empty for an option
  std::string description;
  std::string group;                     ///< the --help group ("Options" when none was given)
  std::string type_name;                 ///< as --help shows it, without the validators: FILE.json, HOST:PORT, S
  std::vector<std::string> checks;       ///< the validators' descriptions: "INT in [1 - 65535]", "POSITIVE", ...
  std::string default_value;             ///< the built-in default as text; empty when there is none
  int values_min = 0;                    ///< values after the option: 0/0 a flag, 0/1 an optional value
  int values_max = 0;
  bool repeatable = false;               ///< may be given more than once (-vv, --dialect A --dialect B)
  char delimiter = '\0';                 ///< one value may list several, split at this character
  bool required = false;
  bool configurable = true;              ///< may be set from the --config file
  bool help = false;                     ///< -h/--help or --version: ends the command line
  ValueKind kind = ValueKind::None;
  std::vector<std::string> choices;      ///< for ValueKind::Choice
  std::string file_pattern;              ///< for ValueKind::File: "*.json", or empty for any file
  std::vector<std::string> excludes;     ///< the options it cannot be given with, by their first spelling

  bool is_flag() const { return values_max == 0; }
  bool optional_value() const { return values_min == 0 && values_max > 0; }
  /// Every spelling: "-i", "--target-ip", "--mavlink-addr".
  std::vector<std::string> spellings() const;
  /// The key in the config file (the first long name; the name of a positional).
  std::string config_key() const;
};

struct CommandModel {
  std::vector<std::string> path;  ///< {"params", "show"}; empty for hitl itself
  std::string description;
  std::string footer;
  std::vector<OptionModel> options;   ///< its own options and positionals, option groups included, hidden ones left out
  std::vector<CommandModel> commands; ///< visible subcommands, in declaration order
  bool fallthrough = false;           ///< options it does not know go to its parent: the parent's options work here too
  bool needs_command = false;         ///< one of `commands` must follow

  std::string name() const { return path.empty() ? std::string() : path.back(); }
  /// "hitl params show".
  std::string full_name(const std::string& program = "hitl") const;
  std::vector<const OptionModel*> positionals() const;
};

/// Reads the model of `app` and its visible subcommands. Call it before parsing: option defaults
/// are read from the variables the options are bound to. Non-const because CLI11 gives validators
/// and defaults only through non-const calls; the app is left as it was, except that each
/// option's default text is captured.
CommandModel read_command_model(CLI::App& app);

/// The model of one option as it stands (its default text as already captured): what `--help`
/// shows while the command line is being parsed.
OptionModel read_option_model(const CLI::Option& option);

/// Every command of the tree, depth first, `root` first.
std::vector<const CommandModel*> all_commands(const CommandModel& root);

/// The options accepted on the command line of `command` (found by path from `root`): its own,
/// then, while a command falls through, its parent's; the first spelling wins, so a command's
/// own -h/--help hides its parent's. Positionals are not included.
std::vector<const OptionModel*> accepted_options(const CommandModel& root, const std::vector<std::string>& path);

/// A description cut to one line for a completion menu: up to the first "; " or " (" when that
/// leaves a phrase, then at most `max_chars` at a word boundary.
std::string summary(const std::string& description, std::size_t max_chars = 90);

/// The command at `path` below `root`, or nullptr.
const CommandModel* find_command(const CommandModel& root, const std::vector<std::string>& path);

}  // namespace hitl::cli
