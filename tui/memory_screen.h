// A screen in memory, for tests: a grid of cells with their styles, read back by position.
#pragma once

#include <string>
#include <vector>

#include "tui/screen.h"

namespace hitl::tui {

class MemoryScreen : public Screen {
 public:
  MemoryScreen(int width, int height, GraphSymbols symbols = GraphSymbols::Braille);
  int width() const override { return width_; }
  int height() const override { return height_; }
  void clear() override;
  void text(int x, int y, std::string_view text, Style style = {}) override;
  void glyph(int x, int y, char32_t ch, Style style = {}) override;
  GraphSymbols graph_symbols() const override { return symbols_; }
  void box(const Rect& r, std::string_view title, Style style = {}) override;
  void flush() override { ++flushes_; }

  /// Row y as text (trailing blanks kept: width() characters); a cell outside ASCII shows as '*'.
  /// row_utf8() has them as they are.
  std::string row(int y) const;
  /// The whole screen, rows joined by '\n'.
  std::string dump() const;
  std::string row_utf8(int y) const;
  /// The cell's character ('\0' off the screen).
  char32_t glyph_at(int x, int y) const;
  char at(int x, int y) const;
  Style style_at(int x, int y) const;
  /// The first (x, y) where `needle` appears on one row; {-1, -1} when nowhere.
  std::pair<int, int> find(std::string_view needle) const;
  int flushes() const { return flushes_; }

 private:
  struct Cell {
    char32_t ch = U' ';
    Style style;
  };
  void put(int x, int y, char32_t ch, Style style);
  int width_;
  int height_;
  std::vector<Cell> cells_;
  int flushes_ = 0;
  GraphSymbols symbols_;
};

}  // namespace hitl::tui
