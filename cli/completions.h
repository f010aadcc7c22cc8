// Shell completion scripts generated from the command model (cli/command_model.h): what
// `hitl completion bash|zsh|fish` prints and completions/ holds.
#pragma once

#include <string>
#include <vector>

#include "cli/command_model.h"

namespace hitl::cli {

/// `message_names` are offered for options typed value_type::kMessageList / kMessageRateList.
/// `fault_names` (engine/faults' catalogue) for options typed value_type::kFaultSpec: the name,
/// then the user types its arguments.
std::string bash_completion(const CommandModel& root, const std::vector<std::string>& message_names,
                            const std::vector<std::string>& fault_names = {});
std::string zsh_completion(const CommandModel& root, const std::vector<std::string>& message_names,
                           const std::vector<std::string>& fault_names = {});
std::string fish_completion(const CommandModel& root, const std::vector<std::string>& message_names,
                            const std::vector<std::string>& fault_names = {});

}  // namespace hitl::cli
