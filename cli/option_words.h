// An option of the command model in words, for the man page and the config reference: its unit,
// the values it accepts, its value as a TOML type.
#pragma once

#include <string>

#include "cli/command_model.h"

namespace hitl::cli {

/// The unit of an option's value, from its type name (S, MS, HZ, PCT, M) or from its description
/// ("ODOMETRY rate, Hz", "Seconds to wait ..."); empty when it has none.
std::string option_unit(const OptionModel& option);

/// What the validators accept, in words: "one of 1.0, 2.0", "1 to 65535", "greater than 0",
/// "an existing file"; empty when anything of the type goes.
std::string option_constraints(const OptionModel& option);

/// The value as the config file writes it: "true / false", "integer", "number", "string",
/// "list of strings", with the type name where it says more ("string (HOST:PORT)").
std::string toml_value_type(const OptionModel& option);

}  // namespace hitl::cli
