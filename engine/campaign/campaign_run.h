// A campaign's flights run as child processes (`hitl campaign run FILE --only INDEX`), N at a time:
// a crashed or hung flight (past the campaign's wall-clock limit it is killed) never stops the
// others, and its result says why. Each child runs in its own process group with its output in
// the flight's log.txt. Stopping (Ctrl-C) ends every child; a flight it stopped has no result, so
// a resumed run flies it again. Never prints: what happens goes to an observer.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "engine/campaign/flight.h"
#include "engine/campaign/flight_run.h"

namespace hitl::campaign {

/// Which flights a run flies when the results folder already holds results.
enum class RunMode {
  Fresh,        ///< a folder with results is refused (so nothing is overwritten by mistake)
  Resume,       ///< only flights without a result
  RerunFailed,  ///< flights without a result and those that failed or erred
};

struct RunOptions {
  std::string out_dir;
  std::size_t jobs = 1;
  RunMode mode = RunMode::Fresh;
  std::string program;  ///< the executable a child runs (this hitl)
  /// The child's arguments (after the program's name) for a flight.
  std::function<std::vector<std::string>(const Flight&)> child_args;
  double stop_grace_s = 5;  ///< after a stop, how long children get before SIGKILL
};

struct Progress {
  std::size_t total = 0;    ///< flights this run flies
  std::size_t done = 0;     ///< of them, finished (passed, failed or error)
  std::size_t passed = 0;
  std::size_t failed = 0;   ///< failed or error
  std::size_t running = 0;
  std::size_t kept = 0;     ///< flights whose earlier result this run keeps (--resume)
  double elapsed_s = 0;
  std::optional<double> eta_s;  ///< once a flight finished
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void on_started(const Flight& /*flight*/, pid_t /*pid*/) {}
  virtual void on_finished(const Flight& /*flight*/, const FlightResult& /*result*/) {}
  virtual void on_progress(const Progress& /*progress*/) {}  ///< after every change, and every second
};

struct RunOutcome {
  Progress progress;
  bool stopped = false;
  double wall_s = 0;
  /// Every flight's result on disk after the run (this run's and kept ones), by index; none: missing.
  std::vector<std::optional<FlightResult>> results;
};

/// Runs the flights. An Error when the results folder cannot be made, or (Fresh) already holds results.
Expected<RunOutcome> run_campaign(const Campaign& campaign, const std::vector<Flight>& flights, const RunOptions& options,
                                  const std::atomic<bool>& stop, RunObserver& observer);

/// Every flight's result.json in `out_dir`, by index (none: missing or unreadable).
std::vector<std::optional<FlightResult>> read_results(const std::string& out_dir, const std::vector<Flight>& flights);

/// "killed by signal 9 (SIGKILL)", "exited with status 3": a wait status in words.
std::string wait_status_text(int status);

}  // namespace hitl::campaign
