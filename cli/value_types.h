// Type names (CLI11's ->type_name) that say what an option's value is. --help shows them, and the
// completion, man page and config generators (cli/command_model.cpp) read them from the model:
// an option typed kMessageList completes MAVLink message names, one typed FILE.json completes
// *.json files. Give an option one of these and every generated file picks it up.
#pragma once

namespace hitl::cli::value_type {

/// MAVLink message names, comma-separated (inspect --show).
inline constexpr const char* kMessageList = "MESSAGE[,MESSAGE]";
/// MAVLink message names with a rate each, comma-separated (inspect --expect).
inline constexpr const char* kMessageRateList = "MESSAGE=HZ[,MESSAGE=HZ]";
/// What a type name starts with when its value is a file: FILE, or FILE.ext for *.ext files.
inline constexpr const char* kFilePrefix = "FILE";
/// The config file (--config).
inline constexpr const char* kConfigFile = "FILE.toml";

}  // namespace hitl::cli::value_type
