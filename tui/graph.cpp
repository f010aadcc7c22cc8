#include "tui/graph.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hitl::tui {

unsigned braille_bit(int dx, int dy) {
  static constexpr unsigned kBits[2][4] = {{0x01, 0x02, 0x04, 0x40}, {0x08, 0x10, 0x20, 0x80}};
  return kBits[dx & 1][dy & 3];
}

std::vector<double> resample(const std::vector<double>& samples, std::size_t capacity, int columns) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> out(static_cast<std::size_t>(std::max(0, columns)), nan);
  if (columns <= 0 || capacity == 0) return out;
  const std::size_t n = std::min(samples.size(), capacity);
  const std::size_t first_slot = capacity - n;  // the window's slot of samples[size - n]
  const std::size_t skip = samples.size() - n;
  for (int c = 0; c < columns; ++c) {
    // Column c covers window slots [begin, end): at least one slot each.
    const auto begin = static_cast<std::size_t>(static_cast<double>(c) * static_cast<double>(capacity) / columns);
    auto end = static_cast<std::size_t>(static_cast<double>(c + 1) * static_cast<double>(capacity) / columns);
    end = std::max(end, begin + 1);
    double sum = 0;
    int count = 0;
    for (std::size_t slot = begin; slot < end && slot < capacity; ++slot) {
      if (slot < first_slot) continue;
      const double v = samples[skip + slot - first_slot];
      if (!std::isfinite(v)) continue;
      sum += v;
      ++count;
    }
    if (count > 0) out[static_cast<std::size_t>(c)] = sum / count;
  }
  return out;
}

std::vector<std::u32string> plot(const std::vector<double>& samples, std::size_t capacity, int width, int height, double lo,
                                 double hi, GraphSymbols symbols) {
  std::vector<std::u32string> rows(static_cast<std::size_t>(std::max(0, height)),
                                   std::u32string(static_cast<std::size_t>(std::max(0, width)), U' '));
  if (width <= 0 || height <= 0) return rows;
  const bool braille = symbols == GraphSymbols::Braille;
  const int dots_x = braille ? 2 : 1, dots_y = braille ? 4 : 3;
  const int levels = height * dots_y;  // dot rows, 0 at the bottom
  const auto columns = resample(samples, capacity, width * dots_x);
  const double span = hi > lo ? hi - lo : 1.0;
  auto level_of = [&](double v) {
    const double f = std::clamp((v - lo) / span, 0.0, 1.0);
    return std::clamp(static_cast<int>(std::lround(f * (levels - 1))), 0, levels - 1);
  };
  std::vector<unsigned> masks(static_cast<std::size_t>(width * height), 0);
  int previous = -1;
  for (int c = 0; c < static_cast<int>(columns.size()); ++c) {
    const double v = columns[static_cast<std::size_t>(c)];
    if (!std::isfinite(v)) {
      previous = -1;
      continue;
    }
    const int level = level_of(v);
    int from = level, to = level;
    if (braille && previous >= 0) {  // join to the previous column: the dots in between, in this one
      from = std::min(level, previous < level ? previous + 1 : previous - 1);
      to = std::max(level, previous < level ? previous + 1 : previous - 1);
      if (previous == level) from = to = level;
    }
    for (int l = from; l <= to; ++l) {
      const int row = height - 1 - l / dots_y;        // cell row from the top
      const int dy = dots_y - 1 - l % dots_y;          // dot row inside the cell from its top
      const int cell = c / dots_x, dx = c % dots_x;
      auto& m = masks[static_cast<std::size_t>(row * width + cell)];
      if (braille) m |= braille_bit(dx, dy);
      else m = static_cast<unsigned>(dy + 1);  // 1 top, 2 middle, 3 bottom
    }
    previous = level;
  }
  for (int row = 0; row < height; ++row)
    for (int x = 0; x < width; ++x) {
      const unsigned m = masks[static_cast<std::size_t>(row * width + x)];
      if (m == 0) continue;
      rows[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)] =
          braille ? kBrailleBase + m : (m == 1 ? U'\'' : m == 2 ? U'-' : U'_');
    }
  return rows;
}

void overlay(std::vector<std::u32string>& bottom, const std::vector<std::u32string>& top) {
  auto is_braille = [](char32_t c) { return c >= kBrailleBase && c <= kBrailleBase + 0xFF; };
  for (std::size_t r = 0; r < bottom.size() && r < top.size(); ++r)
    for (std::size_t x = 0; x < bottom[r].size() && x < top[r].size(); ++x) {
      const char32_t t = top[r][x];
      if (t == U' ') continue;
      char32_t& b = bottom[r][x];
      b = is_braille(t) && is_braille(b) ? (b | t) : t;
    }
}

std::pair<double, double> range_of(const std::vector<std::vector<double>>& series, double min_span) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : series)
    for (double v : s)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  if (!std::isfinite(lo)) return {0.0, min_span};
  if (hi - lo < min_span) {
    const double mid = (hi + lo) / 2;
    lo = mid - min_span / 2;
    hi = mid + min_span / 2;
  }
  return {lo, hi};
}

GraphSymbols choose_graph_symbols(const char* graph_symbol_env, bool utf8_locale, const char* term) {
  const std::string_view env = graph_symbol_env != nullptr ? graph_symbol_env : "";
  if (env == "ascii") return GraphSymbols::Ascii;
  if (env == "braille") return GraphSymbols::Braille;
  const bool linux_console = term != nullptr && std::string_view(term) == "linux";
  return utf8_locale && !linux_console ? GraphSymbols::Braille : GraphSymbols::Ascii;
}

std::string utf8(char32_t ch) {
  std::string out;
  if (ch < 0x80) {
    out += static_cast<char>(ch);
  } else if (ch < 0x800) {
    out += static_cast<char>(0xC0 | (ch >> 6));
    out += static_cast<char>(0x80 | (ch & 0x3F));
  } else if (ch < 0x10000) {
    out += static_cast<char>(0xE0 | (ch >> 12));
    out += static_cast<char>(0x80 | ((ch >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (ch & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (ch >> 18));
    out += static_cast<char>(0x80 | ((ch >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((ch >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (ch & 0x3F));
  }
  return out;
}

}  // namespace hitl::tui
