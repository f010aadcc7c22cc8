// Options every subcommand shares, and the helpers that turn engine results into output.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/mavlink/message_set.h"

namespace hitl::cli {

// The exit codes of every command, the one table (README "Exit codes", the man page's EXIT STATUS;
// tests/cli/exit_codes_e2e_test.cpp holds each command to it).
/// Success: the command did what it was asked, every check passed.
inline constexpr int kExitOk = 0;
/// A check failed, the board refused a command, no board answered (no HEARTBEAT, or every send to
/// it refused), or nothing a session sent was delivered.
inline constexpr int kExitFailed = 1;
/// Bad usage or input: an unknown option, a bad value or file, an address or port that cannot be
/// opened (a port in use): the command could not start.
inline constexpr int kExitUsage = 2;

/// The exit code for an engine error, from its kind: the one place kinds meet the table above.
/// Usage (the command line), Input (a file or value) and Unavailable (a port in use, an address that
/// cannot be opened) stopped the command before it ran: 2. Failed (no answer, refused, a check
/// failed, the adb path did not come up) is a command that ran: 1.
constexpr int exit_code(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Usage: return kExitUsage;
    case ErrorKind::Input: return kExitUsage;
    case ErrorKind::Unavailable: return kExitUsage;
    case ErrorKind::Failed: return kExitFailed;
  }
  return kExitFailed;
}
inline int exit_code(const Error& error) { return exit_code(error.kind); }

struct GlobalOptions {
  bool json = false;                   ///< --json: JSON lines on stdout, a final summary object last
  int verbosity = 0;                   ///< -v (repeatable)
  bool quiet = false;                  ///< -q: results only
  std::vector<std::string> dialects;   ///< --dialect FILE.xml (repeatable), plus $HITL_MAVLINK_DIALECT
};

/// Adds --json, -v/--verbose, -q/--quiet, --dialect and --config to the top-level app.
void add_global_options(CLI::App& app, GlobalOptions& options);

/// The compiled-in messages plus every dialect from --dialect and $HITL_MAVLINK_DIALECT.
Expected<mavlink::MessageSet> load_messages(const GlobalOptions& options);

/// One JSON object on one line of stdout, flushed; invalid UTF-8 from the network is replaced.
void print_json_line(const nlohmann::json& object);

/// A line on stderr for progress and diagnostics, unless --quiet.
void log_info(const GlobalOptions& options, const std::string& line);
/// An error line on stderr: "hitl <cmd>: <message>".
void log_error(const std::string& command, const std::string& message);
/// log_error() of the error's message; returns its exit code (from its kind, exit_code()).
int log_error(const std::string& command, const Error& error);

/// Installs SIGINT/SIGTERM handlers; the flag turns true on the first signal (a second one kills).
const std::atomic<bool>& stop_flag_on_signals();

bool stdout_is_tty();
/// True when this process is a background job of the terminal its stderr goes to (`hitl target &`):
/// its terminal's foreground process group is another (the shell's next command).
bool background_job_of_terminal();

}  // namespace hitl::cli
