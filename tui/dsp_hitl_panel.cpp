// dsp_hitl: the board's counters with the rates derived from them, a stop mark when one stalls.
#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {

void draw_unavailable(Screen& screen, const Rect& in, const std::string& reason) {
  int y = in.y;
  for (const auto& line : wrap("n/a: " + reason, in.w)) {
    if (y >= in.y + in.h) break;
    put(screen, in, in.x, y++, line, {Color::Dim, false, false});
  }
}

void draw_dsp_hitl(Screen& screen, const Rect& r, const DspHitlPanel& panel) {
  const bool stopped = !panel.unavailable && !panel.counters.empty() && !panel.running;
  screen.box(r, stopped ? "dsp_hitl: NOT RUNNING" : "dsp_hitl (board, Hz)", stopped ? health_style(Health::Bad) : Style{});
  const Rect in = r.inner();
  if (in.empty()) return;
  if (panel.unavailable) return draw_unavailable(screen, in, *panel.unavailable);
  if (panel.counters.empty()) return put(screen, in, in.x, in.y, "waiting for the first status", {Color::Dim, false, false});
  // Narrow: short names (12); wide: the status text's own labels, a header and the poll's age.
  const bool wide = in.w >= 12 + 9 + 7 + 5 + 5 + 17 && in.h >= 7;
  const int name_w = wide ? 29 : 12;
  int y = in.y;
  if (wide) put(screen, in, in.x, y++, fit("counter", name_w) + right("count", 9) + right("rate", 7) + right("exp", 5) + " state",
                {Color::Dim, false, false});
  for (const auto& c : panel.counters) {
    if (y >= in.y + in.h) break;
    const Style hs = health_style(c.stalled ? Health::Bad : c.health);
    int x = in.x;
    auto cell = [&](const std::string& text, Style style = {}) {
      put(screen, in, x, y, text, style);
      x += static_cast<int>(text.size());
    };
    cell(fit(wide ? c.name : c.short_name, name_w));
    cell(right(std::to_string(c.count), 9));
    cell(right(c.rate_hz ? rate(*c.rate_hz) : "-", 7), c.rate_hz ? hs : Style{});
    cell(right(c.expected_hz > 0 ? format("%.0f", c.expected_hz) : "-", 5));
    cell(" ");
    cell(c.stalled ? "STOP" : (c.rate_hz ? telemetry::to_string(c.health) : "..."), c.rate_hz || c.stalled ? hs : Style{});
    ++y;
  }
  if (wide && y < in.y + in.h && panel.age_s >= 0)
    put(screen, in, in.x, y, format("polled %.1f s ago through the MAVLink shell", panel.age_s), {Color::Dim, false, false});
}

}  // namespace hitl::tui
