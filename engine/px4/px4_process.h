// PX4 SITL as a child process that hitl started and owns (hitl sim --px4): started in a fresh
// working folder as instance N with the airframe that waits for a simulator (10016 none_iris) and
// the parameters hitl gives, its console to a file, watched while it runs and stopped at the end.
// It never touches a process it did not start: it signals only its own child's process group.
// PX4 and everything it starts (its start script's shell and module clients) die with hitl even on
// SIGKILL: a small supervisor process between them (PR_SET_PDEATHSIG) kills PX4's process group.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/common/expected.h"
#include "base/common/severity.h"
#include "engine/px4/px4_build.h"
#include "engine/px4/px4_instance.h"

namespace hitl::px4 {

/// A parameter PX4 sets at boot from PX4_PARAM_<name> (its rcS runs `param set name value`).
struct Px4Param {
  std::string name;
  std::string value;
};

/// "NAME=VALUE" -> the parameter, or an input Error (PX4's names: A-Z, 0-9, _; at most 16 characters;
/// the value a number).
Expected<Px4Param> parse_px4_param(std::string_view text);

struct Px4StartOptions {
  Px4Instance instance;
  std::string work_dir;      ///< PX4's working folder (-w): created when missing; its parameters and logs stay there
  std::string console_path;  ///< PX4's standard output and error
  std::vector<Px4Param> params;  ///< in order; a later one of the same name wins
  double speed_factor = 1.0;     ///< PX4_SIM_SPEED_FACTOR: lockstep at this many times real time
};

/// Reads PX4's console file as it grows, a line at a time.
class Px4Console {
 public:
  explicit Px4Console(std::string path) : path_(std::move(path)) {}
  /// The complete lines written since the last call (at most `max_bytes` read per call).
  std::vector<std::string> new_lines(std::size_t max_bytes = 64 * 1024);
  /// The last `n` lines of the file (for a message when PX4 died).
  std::vector<std::string> last_lines(std::size_t n) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  uint64_t offset_ = 0;
  std::string partial_;
};

/// PX4's console line "WARN  [commander] ..." -> Warning, "ERROR [...]" -> Error (terminal colour
/// codes ignored); nullopt for INFO and anything else.
std::optional<Severity> px4_console_severity(std::string_view line);
/// NAME from PX4's console line "ERROR [param] Parameter NAME not found." (its `param set` for a
/// PX4_PARAM_ it does not have); nullopt for any other line.
std::optional<std::string> px4_unknown_parameter(std::string_view line);
/// The line without PX4's terminal colour codes.
std::string without_colour_codes(std::string_view line);
/// The line without the "pxh> " prompts a MAVLink shell session leaves at its start.
std::string without_shell_prompt(std::string line);

class Px4Process {
 public:
  /// Starts PX4: `program -d -i N -w work_dir etc_dir` with PX4_SYS_AUTOSTART=10016,
  /// PX4_SIM_MODEL=none_iris, the speed factor and PX4_PARAM_* in its environment
  /// (PX4_SIM_HOSTNAME / PX4_SIM_HOST_ADDR removed: it connects to 127.0.0.1).
  static Expected<std::unique_ptr<Px4Process>> start(const Px4Build& build, const Px4StartOptions& options);
  ~Px4Process();
  Px4Process(const Px4Process&) = delete;
  Px4Process& operator=(const Px4Process&) = delete;

  pid_t pid() const { return pid_; }
  /// nullopt while it runs; once it ended, its exit code (128 + the signal that ended it).
  std::optional<int> exited();
  /// Stops it and waits: SIGTERM, then SIGKILL after `grace_s`; `kill_now`: SIGKILL at once (before
  /// its first HIL_SENSOR PX4 ignores SIGTERM). Returns its exit code. Safe to call again.
  int stop(bool kill_now, double grace_s = 5.0);
  Px4Console& console() { return console_; }
  const Px4StartOptions& options() const { return options_; }

 private:
  Px4Process(pid_t pid, pid_t supervisor, Px4StartOptions options)
      : pid_(pid), supervisor_(supervisor), options_(std::move(options)), console_(options_.console_path) {}
  pid_t pid_;         ///< PX4, the leader of its own process group
  pid_t supervisor_;  ///< hitl's child that started PX4: kills PX4's group when hitl dies, exits with PX4's code
  Px4StartOptions options_;
  Px4Console console_;
  std::optional<int> exit_code_;
};

}  // namespace hitl::px4
