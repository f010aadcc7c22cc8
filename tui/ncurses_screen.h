// The screen on a real terminal through ncurses: stdscr is the off-screen frame, flush() sends
// the difference once (refresh). Colours by meaning, with a monochrome fallback (bold, reverse,
// dim) when the terminal has none; the panels also print health as words, so nothing depends
// on colour alone.
#pragma once

#include "tui/key.h"
#include "tui/screen.h"

namespace hitl::tui {

/// The ncurses attributes and colour pair of a style (pair 0: the terminal's default colours).
struct CursesLook {
  short pair = 0;
  unsigned long attributes = 0;  ///< A_* bits
};
CursesLook curses_look(const Style& style, bool colour);

class NcursesScreen : public Screen {
 public:
  /// Call after the terminal is in curses mode (terminal.h); sets up the colour pairs. `symbols`:
  /// how graphs are drawn (choose_graph_symbols: braille needs a UTF-8 locale and ncursesw).
  explicit NcursesScreen(GraphSymbols symbols);
  int width() const override;
  int height() const override;
  void clear() override;
  void text(int x, int y, std::string_view text, Style style = {}) override;
  void glyph(int x, int y, char32_t ch, Style style = {}) override;
  GraphSymbols graph_symbols() const override { return symbols_; }
  void box(const Rect& r, std::string_view title, Style style = {}) override;
  void flush() override;

  bool colour() const { return colour_; }
  /// Waits up to `timeout_ms` for a key and decodes it once (KEY_RESIZE: the size changed).
  Key read_key(int timeout_ms);

 private:
  bool colour_ = false;
  GraphSymbols symbols_;
};

}  // namespace hitl::tui
