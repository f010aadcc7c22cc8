// An option of the command model in words, for the man page and the config reference: its unit,
// the values it accepts, its value as a TOML type.
#pragma once

#include <string>
#include <vector>

#include "cli/command_model.h"

namespace hitl::cli {

/// The unit of an option's value, from its type name (S, MS, HZ, PCT, M) or from its description
/// ("ODOMETRY rate, Hz", "Seconds to wait ..."); empty when it has none.
std::string option_unit(const OptionModel& option);

/// What the validators accept, in words: "one of 1.0, 2.0", "1 to 65535", "greater than 0",
/// "an existing file"; empty when anything of the type goes.
std::string option_constraints(const OptionModel& option);

/// The constraints with the kind of number first where the type says it: "an integer, 1 to
/// 65535", "a number, greater than 0", "a number"; as option_constraints otherwise.
std::string option_accepts(const OptionModel& option);

/// The word that stands for the value after the option, in --help and the man page: the type name
/// where it says what the value is (FILE.tlog, HOST:PORT, S, HZ), "a|b" for a choice, and for
/// CLI11's own TEXT, INT, UINT, FLOAT the option's name as argparse writes it (--hil-port HIL_PORT);
/// a positional's name; empty for a flag.
std::string option_metavar(const OptionModel& option);

/// `text` ending in a full stop (none added after "." "!" "?"), trailing spaces dropped.
std::string as_sentence(std::string text);

/// The word after the option on its tag line: the metavar, in brackets when the value may be left
/// out (and not already bracketed by its type name); empty for a flag.
std::string option_value_tag(const OptionModel& option);

/// The sentences after an option's description: what it accepts, its default (with its unit),
/// the options it cannot be given with, repeatable, required. The man page and --help print them.
std::vector<std::string> option_notes(const OptionModel& option);

/// The value as the config file writes it: "true / false", "integer", "number", "string",
/// "list of strings", with the type name where it says more ("string (HOST:PORT)").
std::string toml_value_type(const OptionModel& option);

}  // namespace hitl::cli
