// hitl: hardware-in-the-loop simulation and diagnostics for PX4 on a VOXL2 / M0197.
#include <CLI/CLI.hpp>

#include <iostream>

#include "cli/commands.h"
#include "cli/common_options.h"
#include "cli/number_check.h"
#include "cli/help_format.h"
#include "cli/parse_errors.h"
#include "cli/version.h"

int main(int argc, char** argv) {
  using namespace hitl::cli;
  CLI::App app{
      "hitl: run and diagnose hardware-in-the-loop simulation of a PX4 x500 whose flight stack runs on a "
      "ModalAI VOXL2 / M0197 board.",
      "hitl"};
  app.formatter(std::make_shared<HelpFormatter>());  // before the subcommands: they copy it
  app.set_version_flag("--version", std::string("hitl ") + kVersion);
  app.require_subcommand(1);
  app.fallthrough();
  app.footer(
      "Exit codes: 0 success; 1 a check failed, the board refused or did not answer; 2 bad usage or input.\n"
      "Run `hitl COMMAND --help` for a command's options.");

  GlobalOptions options;
  RunState state;
  add_global_options(app, options);
  add_inspect_command(app, options, state);
  add_sim_command(app, options, state);
  add_target_command(app, options, state);
  add_replay_command(app, options, state);
  add_params_command(app, options, state);
  add_arm_commands(app, options, state);
  add_shell_command(app, options, state);
  add_fly_command(app, options, state);
  add_doctor_command(app, options, state);
  add_board_command(app, options, state);
  add_bridge_command(app, options, state);
  add_demo_command(app, options, state);
  add_campaign_command(app, options, state);
  add_report_command(app, options, state);
  add_completion_command(app, options, state);
  add_reference_command(app, options, state);
  add_number_checks(app);  // every number option: finite, of sane size (cli/number_check.h)

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    std::string config_file;
    for (std::size_t i = 0; i + 1 < args.size(); ++i)
      if (args[i] == "--config") config_file = args[i + 1];
    for (const auto& a : args)
      if (a.rfind("--config=", 0) == 0) config_file = a.substr(9);
    if (const auto better = explain_parse_error(app, e, args, config_file); !better.empty()) {
      std::cerr << better << '\n';
      return exit_code(hitl::ErrorKind::Usage);  // CLI11 refused the command line
    }
    app.exit(e);
    return exit_code(hitl::ErrorKind::Usage);  // CLI11 refused the command line
  }
  return state.exit_code;
}
