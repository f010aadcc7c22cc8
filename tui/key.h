// A key, decoded once from raw input by the screen (ncurses_screen.h); keys.h turns keys into actions.
#pragma once

namespace hitl::tui {

struct Key {
  enum class Kind { None, Char, Enter, Escape, Backspace, Resize, PageUp, PageDown, Home, End, Up, Down };
  Kind kind = Kind::None;
  char ch = 0;  ///< Char: a printable ASCII character
  static Key character(char c) { return {Kind::Char, c}; }
};

}  // namespace hitl::tui
