// The terminal in curses mode for the life of one object, and one path that gives it back on every
// exit (btop's clean_quit): the destructor (normal return, exceptions), SIGINT / SIGTERM / SIGHUP
// (the first asks the dashboard to stop, which then restores on its way out; a second restores and
// dies of the signal), and fatal signals (SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL: restore, then
// re-raise). The signal path writes the terminal's own reset strings and the saved termios, both
// async-signal-safe.
#pragma once

#include <memory>
#include <string>

#include "base/common/expected.h"
#include "tui/ncurses_screen.h"

namespace hitl::tui {

/// Whether a dashboard can run here: stdin and stdout are terminals and TERM names one ncurses
/// knows; otherwise why not ("stdout is not a terminal").
Expected<bool> terminal_usable();

class Terminal {
 public:
  static Expected<std::unique_ptr<Terminal>> open();
  ~Terminal();  ///< restores the terminal and the previous signal handlers
  Terminal(const Terminal&) = delete;
  Terminal& operator=(const Terminal&) = delete;

  NcursesScreen& screen() { return *screen_; }
  /// A SIGINT, SIGTERM or SIGHUP arrived (its number), or 0.
  int stop_signal() const;

 private:
  Terminal() = default;
  std::unique_ptr<NcursesScreen> screen_;
  void* curses_screen_ = nullptr;  ///< SCREEN* from newterm
};

}  // namespace hitl::tui
