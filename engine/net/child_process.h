// Running another program (adb) to completion: its output captured, a time limit, never a hang.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/common/expected.h"

namespace hitl::net {

struct ProgramOutput {
  int exit_code = -1;  ///< 128 + signal when a signal ended it
  std::string out;
  std::string err;
};

/// Runs `program` (a path) with `args`, stdin from /dev/null, and waits for it. An Error naming the
/// command when it cannot be started or has not finished within timeout_ms (it is then killed).
/// Output is collected until the program exits; a daemon it leaves behind holding the pipes does
/// not keep the call waiting.
Expected<ProgramOutput> run_program(const std::string& program, const std::vector<std::string>& args, int timeout_ms);

/// The path of the executable `name` in $PATH's directories, or nullopt.
std::optional<std::string> find_on_path(std::string_view name);

/// "adb -s X forward tcp:0 tcp:14590": a command line for messages.
std::string command_line(const std::string& program, const std::vector<std::string>& args);

}  // namespace hitl::net
