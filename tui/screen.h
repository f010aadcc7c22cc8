// Where the dashboard draws: a grid of character cells, each with a colour and attributes. The
// drawing code composes a whole frame off-screen and flushes it once (btop's way); it never asks
// the terminal anything but its size. Two implementations: ncurses (ncurses_screen.h) and an
// in-memory grid for tests (memory_screen.h).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "tui/graph.h"

namespace hitl::tui {

/// Colours by meaning; each screen maps them to what the terminal can show.
enum class Color : uint8_t { Default, Good, Warning, Bad, Accent, Dim };

struct Style {
  Color color = Color::Default;
  bool bold = false;
  bool reverse = false;

  friend bool operator==(const Style&, const Style&) = default;
};

/// A rectangle of cells: column x, row y, width w, height h.
struct Rect {
  int x = 0;
  int y = 0;
  int w = 0;
  int h = 0;
  bool empty() const { return w <= 0 || h <= 0; }
  /// The inside of a box drawn around this rectangle.
  Rect inner() const { return {x + 1, y + 1, w - 2, h - 2}; }
};

class Screen {
 public:
  virtual ~Screen() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  /// Starts a new frame: every cell blank, default style.
  virtual void clear() = 0;
  /// Writes printable ASCII text at (x, y), clipped to the screen; other bytes show as '?'.
  virtual void text(int x, int y, std::string_view text, Style style = {}) = 0;
  /// One cell that may be outside ASCII (a graph's braille, graph.h), clipped to the screen.
  virtual void glyph(int x, int y, char32_t ch, Style style = {}) = 0;
  /// How graphs are drawn here: braille where the terminal shows UTF-8, else ASCII.
  virtual GraphSymbols graph_symbols() const = 0;
  /// A box around `r` with `title` in its top edge.
  virtual void box(const Rect& r, std::string_view title, Style style = {}) = 0;
  /// Shows the frame.
  virtual void flush() = 0;
};

}  // namespace hitl::tui
