// What a campaign run prints while it flies: each flight's board and session events (its log.txt)
// and the run's progress (a line redrawn on a terminal, a line per flight otherwise, JSON status
// lines with --json).
#pragma once

#include <sys/types.h>

#include <mutex>
#include <string>

#include "cli/common_options.h"
#include "emulator/board.h"
#include "engine/campaign/campaign_run.h"
#include "engine/hil/session.h"

namespace hitl::cli {

/// The board's and the session's events in a flight's process (its log.txt): warnings and errors,
/// everything with -v.
class FlightEvents : public target::Board::Observer, public hil::Session::Observer {
 public:
  explicit FlightEvents(const GlobalOptions& g) : g_(g) {}
  void on_event(const target::BoardEvent& e) override;
  void on_event(const hil::SessionEvent& e) override;

 private:
  const GlobalOptions& g_;
  std::mutex mutex_;
};

/// "42s", "3m07s", "1h05m": a duration for the progress line.
std::string duration_text(double s);

/// The progress line on a terminal (redrawn in place on stderr), a line per flight otherwise, or
/// JSON status lines with --json.
class RunPrinter : public campaign::RunObserver {
 public:
  RunPrinter(const GlobalOptions& g, std::string name);
  void on_started(const campaign::Flight& f, pid_t pid) override;
  void on_finished(const campaign::Flight& f, const campaign::FlightResult& r) override;
  void on_progress(const campaign::Progress& p) override;
  /// Clears the redrawn line (before other output).
  void clear_line();

 private:
  const GlobalOptions& g_;
  std::string name_;
  bool tty_;
  bool drawn_ = false;
};

}  // namespace hitl::cli
