// Shell completion scripts generated from the command model (cli/command_model.h): what
// `hitl completion bash|zsh|fish` prints and completions/ holds.
#pragma once

#include <string>
#include <vector>

#include "cli/command_model.h"

namespace hitl::cli {

/// `message_names` are offered for options typed value_type::kMessageList / kMessageRateList.
std::string bash_completion(const CommandModel& root, const std::vector<std::string>& message_names);
std::string zsh_completion(const CommandModel& root, const std::vector<std::string>& message_names);
std::string fish_completion(const CommandModel& root, const std::vector<std::string>& message_names);

}  // namespace hitl::cli
