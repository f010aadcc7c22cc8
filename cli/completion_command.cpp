// hitl completion bash|zsh|fish: the shell completion script, generated from the command model.
#include <algorithm>
#include <iostream>
#include <memory>

#include "cli/command_model.h"
#include "cli/commands.h"
#include "cli/completions.h"
#include "engine/faults/fault_spec.h"

namespace hitl::cli {
namespace {

std::vector<std::string> compiled_message_names() {
  const auto set = mavlink::MessageSet::compiled();
  std::vector<std::string> names;
  for (const auto* desc : set.all()) names.push_back(desc->name);
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

void add_completion_command(CLI::App& app, GlobalOptions&, RunState& state) {
  auto shell = std::make_shared<std::string>();
  auto model = std::make_shared<CommandModel>();
  auto* sub = app.add_subcommand("completion", "Print the shell completion script for bash, zsh or fish");
  sub->add_option("SHELL", *shell, "The shell")->required()->check(CLI::IsMember({"bash", "zsh", "fish"}));
  sub->footer(
      "Examples:\n"
      "  source <(hitl completion bash)                                     # this bash session\n"
      "  hitl completion bash > ~/.local/share/bash-completion/completions/hitl\n"
      "  hitl completion zsh > ~/.zfunc/_hitl                               # a directory in $fpath\n"
      "  hitl completion fish > ~/.config/fish/completions/hitl.fish\n"
      "The installed package puts all three in place. Message names are the compiled-in ones.");
  // The model is read before parsing goes on, while every option still holds its built-in default.
  sub->preparse_callback([&app, model](std::size_t) { *model = read_command_model(app); });
  sub->callback([&state, shell, model]() {
    const auto messages = compiled_message_names();
    const auto faults = faults::fault_names();
    if (*shell == "bash") std::cout << bash_completion(*model, messages, faults);
    else if (*shell == "zsh") std::cout << zsh_completion(*model, messages, faults);
    else std::cout << fish_completion(*model, messages, faults);
    std::cout << std::flush;
    state.exit_code = std::cout ? kExitOk : kExitFailed;
  });
}

}  // namespace hitl::cli
