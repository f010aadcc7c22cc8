// Type names (CLI11's ->type_name) that say what an option's value is. --help shows them, and the
// completion, man page and config generators (cli/command_model.cpp) read them from the model:
// an option typed kMessageList completes MAVLink message names, one typed FILE.json completes
// *.json files. Give an option one of these and every generated file picks it up.
#pragma once

#include <string_view>

namespace hitl::cli::value_type {

/// MAVLink message names, comma-separated (inspect --show).
inline constexpr const char* kMessageList = "MESSAGE[,MESSAGE]";
/// MAVLink message names with a rate each, comma-separated (inspect --expect).
inline constexpr const char* kMessageRateList = "MESSAGE=HZ[,MESSAGE=HZ]";
/// What a type name starts with when its value is a file: FILE, or FILE.ext for *.ext files.
inline constexpr const char* kFilePrefix = "FILE";
/// A fault to start (sim --fault, demo --fault): a name from engine/faults' catalogue, its
/// arguments, its start and duration.
inline constexpr const char* kFaultSpec = "NAME[:ARGS][@T[+DUR]]";
/// The config file (--config).
inline constexpr const char* kConfigFile = "FILE.toml";

/// Type names of a floating-point value: CLI11's FLOAT, and those that say the unit.
inline bool is_floating(std::string_view t) {
  for (std::string_view f : {"FLOAT", "NUMBER", "S", "MS", "HZ", "PCT", "M", "M_S", "DEG", "RAD", "K"})
    if (t == f) return true;
  return false;
}
/// Type names of a whole number: CLI11's INT and UINT, and N.
inline bool is_integer(std::string_view t) { return t == "INT" || t == "UINT" || t == "N"; }
/// CLI11's own type names, which say nothing of the value's meaning: --help shows the option's
/// name in their place, as argparse does (--hil-port HIL_PORT).
inline bool is_generic(std::string_view t) {
  return t.empty() || t == "TEXT" || t == "INT" || t == "UINT" || t == "FLOAT" || t == "NUMBER" || t == "ENUM";
}

}  // namespace hitl::cli::value_type
