// hitl shell: the PX4 shell from the host (SERIAL_CONTROL, as mavlink_shell.py), one command
// with -c or line by line from stdin. Exits 1 when a command returned non-zero on the board (PX4's
// shell says so in its output, shell_status.h), unless --ignore-status.
#include <unistd.h>

#include <iostream>
#include <optional>

#include "cli/commands.h"
#include "cli/line_editor.h"
#include "cli/link_options.h"
#include "cli/number_check.h"
#include "engine/vehicle/shell_client.h"
#include "engine/vehicle/shell_status.h"

namespace hitl::cli {
namespace {

struct ShellOptions {
  vehicle::LinkOptions link;
  std::string command;
  double timeout_s = 5.0;
  bool ignore_status = false;
};

/// --json: one {"type":"shell",...} item per command, then exactly one summary, last (also when it
/// ends on an error): {"type":"summary","command":"shell","commands","failed","ok"[,"error"]}.
struct ShellReport {
  const GlobalOptions& g;
  int commands = 0;
  int failed_on_board = 0;
  std::string error;

  void fail(const std::string& message) {
    log_error("shell", message);
    if (error.empty()) error = message;
  }
  void summary(bool ok) const {
    if (!g.json) return;
    nlohmann::json j = {{"type", "summary"}, {"command", "shell"}, {"commands", commands}, {"failed", failed_on_board}, {"ok", ok}};
    if (!error.empty()) j["error"] = error;
    print_json_line(j);
  }
};

int run_shell(const GlobalOptions& g, const ShellOptions& o, ShellReport& report) {
  auto link = vehicle::VehicleLink::connect(o.link);
  if (!link) {
    report.fail(link.error().message);
    return exit_code(link.error());
  }
  log_info(g, "hitl shell: autopilot " + std::to_string((*link)->target_sysid()) + " " + (*link)->description());
  vehicle::ShellClient shell(**link);
  bool failed_on_board = false;
  auto one = [&](const std::string& line) {
    auto out = shell.run(line, o.timeout_s);
    if (!out) {
      report.fail(out.error().message);
      return false;
    }
    ++report.commands;
    const vehicle::ShellStatus status = vehicle::shell_status(*out);
    if (g.json)
      print_json_line({{"type", "shell"}, {"command", line}, {"output", *out}, {"status", status.code}, {"ok", status.code == 0}});
    else std::cout << *out << std::flush;
    if (status.code != 0) {
      failed_on_board = true;
      ++report.failed_on_board;
      if (!o.ignore_status)
        log_error("shell", "'" + line + "' returned " + std::to_string(status.code) + " on the board (" + status.line +
                               "); --ignore-status to exit 0");
    }
    return true;
  };
  auto exit_code = [&] { return failed_on_board && !o.ignore_status ? kExitFailed : kExitOk; };
  if (!o.command.empty()) return one(o.command) ? exit_code() : kExitFailed;
  // At a terminal: line editing, Up/Down and Ctrl-R over a history kept between runs (libedit).
  // Piped: lines as they come, no prompt, as before.
  std::optional<LineEditor> editor;
  if (::isatty(STDIN_FILENO) == 1) editor.emplace(shell_history_path());
  auto next_line = [&]() -> std::optional<std::string> {
    if (editor) {
      auto typed = editor->read("pxh> ");
      if (!typed) std::cout << '\n' << std::flush;  // Ctrl-D: the next prompt of the terminal starts on its own line
      return typed;
    }
    std::string line;
    if (!std::getline(std::cin, line)) return std::nullopt;
    return line;
  };
  while (auto line = next_line()) {
    if (*line == "exit" || *line == "quit") break;
    if (line->empty()) continue;
    if (!one(*line)) return kExitFailed;
  }
  return exit_code();  // 1 when any command returned non-zero on the board
}

int run_and_report(const GlobalOptions& g, const ShellOptions& o) {
  ShellReport report{g};
  const int code = run_shell(g, o, report);
  report.summary(code == kExitOk);
  return code;
}

}  // namespace

void add_shell_command(CLI::App& app, GlobalOptions& options, RunState& state) {
  auto o = std::make_shared<ShellOptions>();
  auto* sub = app.add_subcommand("shell", "The PX4 shell on the board over MAVLink (one command with -c, or lines from stdin)");
  add_link_options(sub, o->link);
  sub->add_option("-c,--command", o->command, "Run one command and print its output, e.g. \"qshell dsp_hitl status\"");
  sub->add_option("--command-timeout", o->timeout_s, "Seconds a command may take")->capture_default_str()->check(positive_number());
  sub->add_flag("--ignore-status", o->ignore_status,
                "Exit 0 even when a command returned non-zero on the board (PX4's \"Command 'NAME' failed, returned N.\")");
  sub->footer("Exit: 0 ok, 1 a command returned non-zero on the board (or the shell did not answer).\n"
              "Examples:\n  hitl shell -c \"qshell dsp_hitl status\"\n  hitl shell            # interactive; exit with Ctrl-D or 'exit'");
  sub->callback([&options, &state, o]() { state.exit_code = run_and_report(options, *o); });
}

}  // namespace hitl::cli
