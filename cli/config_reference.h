// docs/config.md: every key the --config TOML file takes, per section, with its value, default and
// unit, generated from the command model so that it cannot drift from what hitl accepts.
#pragma once

#include <string>

#include "cli/command_model.h"

namespace hitl::cli {

std::string config_reference(const CommandModel& root);

}  // namespace hitl::cli
