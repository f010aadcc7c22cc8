// hitl reference man|config (hidden): the man page and the config file reference, generated from
// the command model; scripts/regen-completions.sh writes them to docs/hitl.1 and docs/config.md.
#include <iostream>
#include <memory>

#include "cli/command_model.h"
#include "cli/commands.h"
#include "cli/config_reference.h"
#include "cli/man_page.h"
#include "cli/version.h"

namespace hitl::cli {

void add_reference_command(CLI::App& app, GlobalOptions&, RunState& state) {
  auto what = std::make_shared<std::string>();
  auto model = std::make_shared<CommandModel>();
  auto* sub = app.add_subcommand("reference", "Print the man page (roff) or the config file reference (Markdown)");
  sub->group("");  // hidden: for scripts/regen-completions.sh; users read `man hitl` and docs/config.md
  sub->add_option("WHAT", *what, "man or config")->required()->check(CLI::IsMember({"man", "config"}));
  // The model is read before parsing goes on, while every option still holds its built-in default.
  sub->preparse_callback([&app, model](std::size_t) { *model = read_command_model(app); });
  sub->callback([&state, what, model]() {
    if (*what == "man") std::cout << man_page(*model, kManPageTemplate, kVersion);
    else std::cout << config_reference(*model);
    std::cout << std::flush;
    state.exit_code = std::cout ? kExitOk : kExitFailed;
  });
}

}  // namespace hitl::cli
