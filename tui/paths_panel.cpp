// Data paths: one row per path, expected against measured rate, jitter, loss, coloured by health.
#include <algorithm>
#include <cmath>

#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {

void draw_paths(Screen& screen, const Rect& r, const PathsPanel& panel) {
  screen.box(r, "Data paths (Hz, jitter ms)");
  const Rect in = r.inner();
  if (in.empty()) return;
  // The base columns fit 38 cells (80x24): path 8, expect 6, rate 7, jitter 6, loss 5, health 6.
  // Wider panels add max gap, count and the message name while they fit.
  constexpr int kName = 8, kHealth = 6;
  int used = kName + 6 + 7 + 6 + 5 + kHealth;
  bool show_gap = false, show_count = false, show_message = false;
  if (used + 8 <= in.w) {
    show_gap = true;
    used += 8;
  }
  if (used + 11 <= in.w) {
    show_count = true;
    used += 11;
  }
  int name_w = show_gap && used + 3 <= in.w ? 11 : kName;  // room for "actuators"
  if (name_w > kName) used += name_w - kName;
  // Whole names before the message column (a bridge's "tx udp:127.0.0.1:14550"), as room allows.
  std::size_t longest = 0;
  for (const auto& row : panel.rows) longest = std::max(longest, row.name.size() + 1);
  if (static_cast<int>(longest) > name_w) {
    const int extra = std::min(static_cast<int>(longest) - name_w, in.w - used);
    if (extra > 0) {
      name_w += extra;
      used += extra;
    }
  }
  if (used + 23 <= in.w) show_message = true;
  std::string header = fit("path", name_w);
  if (show_message) header += fit("message", 23);
  header += right("expect", 6) + right("rate", 7) + right("jit", 6);
  if (show_gap) header += right("maxgap", 8);
  header += right("loss", 5);
  if (show_count) header += right("count", 11);
  header += " state";
  put(screen, in, in.x, in.y, header, {Color::Dim, false, false});
  int y = in.y + 1;
  if (panel.rows.empty()) put(screen, in, in.x, y, "nothing yet", {Color::Dim, false, false});
  // Rows that do not fit are counted on the last line, never dropped silently.
  const int room = in.h - 1;
  const int total = static_cast<int>(panel.rows.size());
  const int shown = total > room ? std::max(0, room - 1) : total;
  if (shown < total) {
    int failing = 0;
    for (int k = shown; k < total; ++k) failing += panel.rows[static_cast<std::size_t>(k)].health != Health::Good ? 1 : 0;
    put(screen, in, in.x, in.y + in.h - 1,
        format("+%d more", total - shown) + (failing ? format(" (%d not ok)", failing) : std::string(" (all ok)")),
        failing ? health_style(Health::Bad) : Style{Color::Dim, false, false});
  }
  for (int k = 0; k < shown; ++k) {
    const PathRow& row = panel.rows[static_cast<std::size_t>(k)];
    const Style hs = health_style(row.health);
    int x = in.x;
    auto cell = [&](const std::string& text, Style style = {}) {
      put(screen, in, x, y, text, style);
      x += static_cast<int>(text.size());
    };
    cell(fit(row.name, name_w));
    if (show_message) cell(fit(row.message, 23), {Color::Dim, false, false});
    cell(right(row.expected_hz > 0 ? rate(row.expected_hz) : "-", 6));
    cell(right(rate(row.rate_hz), 7), row.note.empty() ? hs : Style{});
    cell(right(row.count >= 3 ? format("%.2f", row.jitter_ms) : "-", 6));
    if (show_gap) cell(right(row.count >= 2 ? format("%.1f", row.max_gap_ms) : "-", 8));
    cell(right(row.loss_pct ? format("%.1f%%", *row.loss_pct) : "-", 5),
         row.loss_pct && *row.loss_pct > 0 ? Style{Color::Warning, false, false} : Style{});
    if (show_count) cell(right(std::to_string(row.count), 11));
    cell(" ");
    cell(fit(row.note.empty() ? telemetry::to_string(row.health) : row.note, kHealth - 1),
         row.note.empty() ? hs : Style{Color::Dim, false, false});
    ++y;
  }
  if (!panel.caption.empty() && shown == total && y < in.y + in.h) put(screen, in, in.x, in.y + in.h - 1, panel.caption, {Color::Dim, false, false});
}

}  // namespace hitl::tui
