#include "tui/draw.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace hitl::tui {

void put(Screen& screen, const Rect& clip, int x, int y, std::string_view text, Style style) {
  if (y < clip.y || y >= clip.y + clip.h) return;
  int begin = 0;
  if (x < clip.x) {
    begin = clip.x - x;
    x = clip.x;
  }
  const int room = clip.x + clip.w - x;
  if (room <= 0 || begin >= static_cast<int>(text.size())) return;
  screen.text(x, y, text.substr(static_cast<std::size_t>(begin), static_cast<std::size_t>(room)), style);
}

std::string fit(std::string_view text, int width) {
  if (width <= 0) return {};
  std::string out(text.substr(0, static_cast<std::size_t>(width)));
  out.resize(static_cast<std::size_t>(width), ' ');
  return out;
}

std::string right(std::string_view text, int width) {
  if (width <= 0) return {};
  const auto w = static_cast<std::size_t>(width);
  if (text.size() >= w) return std::string(text.substr(text.size() - w));
  return std::string(w - text.size(), ' ') + std::string(text);
}

std::vector<std::string> wrap(std::string_view text, int width) {
  std::vector<std::string> lines;
  if (width <= 0) return lines;
  const auto w = static_cast<std::size_t>(width);
  std::string line;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && text[i] == ' ') ++i;
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ') ++j;
    std::string word(text.substr(i, j - i));
    i = j;
    if (word.empty()) break;
    while (word.size() > w) {  // a word longer than a line: cut it
      if (!line.empty()) {
        lines.push_back(line);
        line.clear();
      }
      lines.push_back(word.substr(0, w));
      word.erase(0, w);
    }
    if (line.empty()) line = word;
    else if (line.size() + 1 + word.size() <= w) line += " " + word;
    else {
      lines.push_back(line);
      line = word;
    }
  }
  if (!line.empty()) lines.push_back(std::move(line));
  return lines;
}

std::string bar(double fraction, int width) {
  if (width <= 0) return {};
  if (!std::isfinite(fraction)) return std::string(static_cast<std::size_t>(width), '?');
  const double f = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(std::lround(f * width));
  return std::string(static_cast<std::size_t>(filled), '#') + std::string(static_cast<std::size_t>(width - filled), '-');
}

std::string format(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

std::string number(std::optional<double> value, int decimals) {
  if (!value || !std::isfinite(*value)) return "n/a";
  return format("%.*f", decimals, *value);
}

std::string rate(double hz) {
  if (!std::isfinite(hz)) return "n/a";
  return hz >= 1000 ? format("%.0f", hz) : format("%.1f", hz);
}

Style severity_style(Severity s) {
  switch (s) {
    case Severity::Info: return {};
    case Severity::Notice: return {Color::Accent, false, false};
    case Severity::Warning: return health_style(Health::Degraded);
    case Severity::Error: return health_style(Health::Bad);
  }
  return {};
}

Style health_style(telemetry::Health health) {
  switch (health) {
    case telemetry::Health::Good: return {Color::Good, false, false};
    case telemetry::Health::Degraded: return {Color::Warning, true, false};
    case telemetry::Health::Bad: return {Color::Bad, true, false};
  }
  return {};
}

}  // namespace hitl::tui
