#include "tui/memory_screen.h"

namespace hitl::tui {

MemoryScreen::MemoryScreen(int width, int height, GraphSymbols symbols)
    : width_(width), height_(height), cells_(static_cast<std::size_t>(width * height)), symbols_(symbols) {}

void MemoryScreen::clear() { cells_.assign(cells_.size(), Cell{}); }

void MemoryScreen::put(int x, int y, char32_t ch, Style style) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  cells_[static_cast<std::size_t>(y * width_ + x)] = {ch, style};
}

void MemoryScreen::text(int x, int y, std::string_view text, Style style) {
  for (const char c : text) {
    put(x++, y, (c >= 0x20 && c < 0x7F) ? static_cast<char32_t>(c) : U'?', style);
  }
}

void MemoryScreen::glyph(int x, int y, char32_t ch, Style style) { put(x, y, ch, style); }

void MemoryScreen::box(const Rect& r, std::string_view title, Style style) {
  if (r.w < 2 || r.h < 2) return;
  for (int x = r.x + 1; x < r.x + r.w - 1; ++x) {
    put(x, r.y, '-', style);
    put(x, r.y + r.h - 1, '-', style);
  }
  for (int y = r.y + 1; y < r.y + r.h - 1; ++y) {
    put(r.x, y, '|', style);
    put(r.x + r.w - 1, y, '|', style);
  }
  for (const auto& [x, y] : {std::pair{r.x, r.y}, {r.x + r.w - 1, r.y}, {r.x, r.y + r.h - 1}, {r.x + r.w - 1, r.y + r.h - 1}})
    put(x, y, '+', style);
  if (!title.empty() && r.w > 4) {
    const std::string t = " " + std::string(title.substr(0, static_cast<std::size_t>(r.w - 4))) + " ";
    Style title_style = style;
    title_style.bold = true;
    text(r.x + 1, r.y, t.substr(0, static_cast<std::size_t>(r.w - 2)), title_style);
  }
}

std::string MemoryScreen::row(int y) const {
  std::string out;
  if (y < 0 || y >= height_) return out;
  for (int x = 0; x < width_; ++x) {
    const char32_t c = cells_[static_cast<std::size_t>(y * width_ + x)].ch;
    out += c < 0x80 ? static_cast<char>(c) : '*';
  }
  return out;
}

std::string MemoryScreen::row_utf8(int y) const {
  std::string out;
  if (y < 0 || y >= height_) return out;
  for (int x = 0; x < width_; ++x) out += utf8(cells_[static_cast<std::size_t>(y * width_ + x)].ch);
  return out;
}

char32_t MemoryScreen::glyph_at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return U'\0';
  return cells_[static_cast<std::size_t>(y * width_ + x)].ch;
}

std::string MemoryScreen::dump() const {
  std::string out;
  for (int y = 0; y < height_; ++y) out += row(y) + (y + 1 < height_ ? "\n" : "");
  return out;
}

char MemoryScreen::at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return '\0';
  const char32_t c = cells_[static_cast<std::size_t>(y * width_ + x)].ch;
  return c < 0x80 ? static_cast<char>(c) : '*';
}

Style MemoryScreen::style_at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return {};
  return cells_[static_cast<std::size_t>(y * width_ + x)].style;
}

std::pair<int, int> MemoryScreen::find(std::string_view needle) const {
  for (int y = 0; y < height_; ++y) {
    const auto x = row(y).find(needle);
    if (x != std::string::npos) return {static_cast<int>(x), y};
  }
  return {-1, -1};
}

}  // namespace hitl::tui
