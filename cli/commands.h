// Every subcommand registers itself through one function here; main.cpp wires them.
#pragma once

#include <CLI/CLI.hpp>

#include "cli/common_options.h"

namespace hitl::cli {

/// Set by a subcommand's callback; main returns it.
struct RunState {
  int exit_code = kExitOk;
};

void add_inspect_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_sim_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_target_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_params_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_arm_commands(CLI::App& app, GlobalOptions& options, RunState& state);
void add_shell_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_fly_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_doctor_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_board_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_bridge_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_demo_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_campaign_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_completion_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_reference_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_report_command(CLI::App& app, GlobalOptions& options, RunState& state);
void add_replay_command(CLI::App& app, GlobalOptions& options, RunState& state);

}  // namespace hitl::cli
