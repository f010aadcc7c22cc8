#include "tui/ncurses_screen.h"

#include <curses.h>

#include <string>

namespace hitl::tui {
namespace {

// Colour pairs by meaning (pair 0 is the default).
constexpr short kPairGood = 1, kPairWarning = 2, kPairBad = 3, kPairAccent = 4;

}  // namespace

CursesLook curses_look(const Style& style, bool colour) {
  CursesLook look;
  unsigned long a = A_NORMAL;
  if (style.bold) a |= A_BOLD;
  if (style.reverse) a |= A_REVERSE;
  if (colour) {
    switch (style.color) {
      case Color::Default: break;
      case Color::Good: look.pair = kPairGood; break;
      case Color::Warning: look.pair = kPairWarning; break;
      case Color::Bad: look.pair = kPairBad; break;
      case Color::Accent: look.pair = kPairAccent; break;
      case Color::Dim: a |= A_DIM; break;
    }
  } else {  // monochrome: the grades must still differ
    switch (style.color) {
      case Color::Default:
      case Color::Good: break;
      case Color::Warning: a |= A_BOLD; break;
      case Color::Bad: a |= A_BOLD | A_STANDOUT; break;
      case Color::Accent: a |= A_BOLD; break;
      case Color::Dim: a |= A_DIM; break;
    }
  }
  look.attributes = a;
  return look;
}

NcursesScreen::NcursesScreen(GraphSymbols symbols) : symbols_(symbols) {
  colour_ = has_colors();
  if (colour_) {
    start_color();
    use_default_colors();  // -1: the terminal's own background
    init_pair(kPairGood, COLOR_GREEN, -1);
    init_pair(kPairWarning, COLOR_YELLOW, -1);
    init_pair(kPairBad, COLOR_RED, -1);
    init_pair(kPairAccent, COLOR_CYAN, -1);
  }
}

int NcursesScreen::width() const { return COLS; }
int NcursesScreen::height() const { return LINES; }

void NcursesScreen::clear() { erase(); }

void NcursesScreen::text(int x, int y, std::string_view text, Style style) {
  if (y < 0 || y >= LINES || x >= COLS || text.empty()) return;
  std::string clean(text);
  for (char& c : clean)
    if (c < 0x20 || c >= 0x7F) c = '?';
  if (x < 0) {
    if (static_cast<std::size_t>(-x) >= clean.size()) return;
    clean.erase(0, static_cast<std::size_t>(-x));
    x = 0;
  }
  const int room = COLS - x;
  const auto look = curses_look(style, colour_);
  attr_set(static_cast<attr_t>(look.attributes), look.pair, nullptr);
  // The bottom-right cell cannot be written without scrolling: stop one short there.
  const int n = std::min(static_cast<int>(clean.size()), y == LINES - 1 ? room - 1 : room);
  if (n > 0) mvaddnstr(y, x, clean.c_str(), n);
  attr_set(A_NORMAL, 0, nullptr);
}

void NcursesScreen::glyph(int x, int y, char32_t ch, Style style) {
  // Off the screen, or the bottom-right cell (writing it would scroll).
  if (x < 0 || y < 0 || x >= COLS || y >= LINES || (y == LINES - 1 && x == COLS - 1)) return;
  const auto look = curses_look(style, colour_);
  if (ch < 0x80 || symbols_ == GraphSymbols::Ascii) {
    attr_set(static_cast<attr_t>(look.attributes), look.pair, nullptr);
    mvaddch(y, x, ch >= 0x20 && ch < 0x7F ? static_cast<chtype>(ch) : static_cast<chtype>('?'));
  } else {  // a wide character through ncursesw (the locale is UTF-8: choose_graph_symbols)
    const wchar_t text[2] = {static_cast<wchar_t>(ch), L'\0'};
    cchar_t cell;
    setcchar(&cell, text, static_cast<attr_t>(look.attributes), look.pair, nullptr);
    mvadd_wch(y, x, &cell);
  }
  attr_set(A_NORMAL, 0, nullptr);
}

void NcursesScreen::box(const Rect& r, std::string_view title, Style style) {
  if (r.w < 2 || r.h < 2) return;
  const auto look = curses_look(style, colour_);
  attr_set(static_cast<attr_t>(look.attributes), look.pair, nullptr);
  mvhline(r.y, r.x + 1, ACS_HLINE, r.w - 2);
  mvhline(r.y + r.h - 1, r.x + 1, ACS_HLINE, r.w - 2);
  mvvline(r.y + 1, r.x, ACS_VLINE, r.h - 2);
  mvvline(r.y + 1, r.x + r.w - 1, ACS_VLINE, r.h - 2);
  mvaddch(r.y, r.x, ACS_ULCORNER);
  mvaddch(r.y, r.x + r.w - 1, ACS_URCORNER);
  mvaddch(r.y + r.h - 1, r.x, ACS_LLCORNER);
  if (!(r.y + r.h == LINES && r.x + r.w == COLS)) mvaddch(r.y + r.h - 1, r.x + r.w - 1, ACS_LRCORNER);
  attr_set(A_NORMAL, 0, nullptr);
  if (!title.empty() && r.w > 4) {
    Style t = style;
    t.bold = true;
    text(r.x + 1, r.y, " " + std::string(title.substr(0, static_cast<std::size_t>(r.w - 4))) + " ", t);
  }
}

void NcursesScreen::flush() { refresh(); }

Key NcursesScreen::read_key(int timeout_ms) {
  timeout(timeout_ms);
  const int ch = getch();
  switch (ch) {
    case ERR: return {};
    case KEY_RESIZE: return {Key::Kind::Resize, 0};
    case KEY_PPAGE: return {Key::Kind::PageUp, 0};
    case KEY_NPAGE: return {Key::Kind::PageDown, 0};
    case KEY_HOME: return {Key::Kind::Home, 0};
    case KEY_END: return {Key::Kind::End, 0};
    case KEY_UP: return {Key::Kind::Up, 0};
    case KEY_DOWN: return {Key::Kind::Down, 0};
    case 27: return {Key::Kind::Escape, 0};
    case '\n':
    case '\r':
    case KEY_ENTER: return {Key::Kind::Enter, 0};
    case KEY_BACKSPACE:
    case 127:
    case 8: return {Key::Kind::Backspace, 0};
    default: break;
  }
  if (ch >= 0x20 && ch < 0x7F) return Key::character(static_cast<char>(ch));
  return {};
}

}  // namespace hitl::tui
