#include "tui/terminal.h"

#include <curses.h>
#include <term.h>
#include <termios.h>
#include <langinfo.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <clocale>
#include <cstring>

namespace hitl::tui {
namespace {

// What the signal handlers need, filled before they are installed. Signal handlers can reach no
// object, so this is the one file-level state of the dashboard.
struct RestoreState {
  termios saved{};
  bool have_saved = false;
  char reset[256] = {};        ///< the terminal's own strings: leave the alternate screen, cursor on, attributes off
  std::size_t reset_len = 0;
  std::atomic<int> stop_signal{0};
  std::atomic<bool> restored{false};
};
RestoreState g_restore;

constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};
constexpr int kFatalSignals[] = {SIGSEGV, SIGABRT, SIGBUS, SIGFPE, SIGILL};
struct sigaction g_previous[64];

void append_capability(const char* name) {
  char* cap = tigetstr(const_cast<char*>(name));
  if (cap == nullptr || cap == reinterpret_cast<char*>(-1)) return;
  const std::size_t n = std::strlen(cap);
  if (g_restore.reset_len + n >= sizeof g_restore.reset) return;
  std::memcpy(g_restore.reset + g_restore.reset_len, cap, n);
  g_restore.reset_len += n;
}

/// Async-signal-safe: write(2) and tcsetattr(3) only.
void restore_from_signal() {
  if (g_restore.restored.exchange(true)) return;
  if (g_restore.reset_len > 0) {
    [[maybe_unused]] const ssize_t n = ::write(STDOUT_FILENO, g_restore.reset, g_restore.reset_len);
  }
  if (g_restore.have_saved) ::tcsetattr(STDIN_FILENO, TCSANOW, &g_restore.saved);
}

extern "C" void on_stop_signal(int sig) {
  int expected = 0;
  if (g_restore.stop_signal.compare_exchange_strong(expected, sig)) return;  // the first: the loop stops
  restore_from_signal();  // a second: give the terminal back and die of it
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

extern "C" void on_fatal_signal(int sig) {
  restore_from_signal();
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install(int sig, void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sigaction(sig, &sa, &g_previous[sig]);
}

}  // namespace

Expected<bool> terminal_usable() {
  if (::isatty(STDOUT_FILENO) != 1) return Error::unavailable("stdout is not a terminal");
  if (::isatty(STDIN_FILENO) != 1) return Error::unavailable("stdin is not a terminal (no keys)");
  const char* term = std::getenv("TERM");
  if (term == nullptr || *term == '\0' || std::strcmp(term, "dumb") == 0)
    return Error::unavailable(std::string("TERM is ") + (term == nullptr || *term == '\0' ? "not set" : "dumb"));
  return true;
}

Expected<std::unique_ptr<Terminal>> Terminal::open() {
  if (auto usable = terminal_usable(); !usable) return usable.error();
  g_restore.have_saved = ::tcgetattr(STDIN_FILENO, &g_restore.saved) == 0;
  std::unique_ptr<Terminal> t(new Terminal());
  // The user's character set, so ncursesw can write braille: LC_CTYPE only (LC_NUMERIC would
  // turn every "%.1f" on the screen and in the JSON into the locale's decimal comma).
  std::setlocale(LC_CTYPE, "");
  const bool utf8_locale = std::strcmp(nl_langinfo(CODESET), "UTF-8") == 0;
  // newterm, not initscr: a terminal ncurses does not know is an error here, not an exit().
  SCREEN* s = newterm(nullptr, stdout, stdin);
  if (s == nullptr) return Error::unavailable(std::string("ncurses does not know the terminal type '") + std::getenv("TERM") + "'");
  t->curses_screen_ = s;
  g_restore.reset_len = 0;
  append_capability("rmcup");
  append_capability("cnorm");
  append_capability("sgr0");
  g_restore.restored.store(false);
  g_restore.stop_signal.store(0);
  cbreak();
  noecho();
  nonl();
  keypad(stdscr, TRUE);
  set_escdelay(25);
  curs_set(0);
  for (int sig : kStopSignals) install(sig, on_stop_signal);
  for (int sig : kFatalSignals) install(sig, on_fatal_signal);
  t->screen_ = std::make_unique<NcursesScreen>(choose_graph_symbols(std::getenv("HITL_GRAPH_SYMBOL"), utf8_locale, std::getenv("TERM")));
  return t;
}

Terminal::~Terminal() {
  for (int sig : kStopSignals) sigaction(sig, &g_previous[sig], nullptr);
  for (int sig : kFatalSignals) sigaction(sig, &g_previous[sig], nullptr);
  if (!g_restore.restored.exchange(true)) {
    curs_set(1);
    endwin();
  }
  if (curses_screen_ != nullptr) delscreen(static_cast<SCREEN*>(curses_screen_));
  if (g_restore.have_saved) ::tcsetattr(STDIN_FILENO, TCSANOW, &g_restore.saved);
}

int Terminal::stop_signal() const { return g_restore.stop_signal.load(); }

}  // namespace hitl::tui
