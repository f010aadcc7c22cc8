// Loop latency: HIL_SENSOR to the HIL_ACTUATOR_CONTROLS that answers it; percentiles, then the
// histogram's bins from the first to the last that hold samples, each a bar against the fullest.
#include <algorithm>

#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {

void draw_latency(Screen& screen, const Rect& r, const LatencyPanel& p) {
  screen.box(r, "Loop latency (" + p.matched + ")");
  const Rect in = r.inner();
  if (in.empty()) return;
  if (p.count == 0) {
    draw_unavailable(screen, in, "no HIL_ACTUATOR_CONTROLS has answered a HIL_SENSOR yet");
    return;
  }
  auto ms = [](double us) { return format("%.2f", us / 1000.0); };
  const Style late = p.limit_us > 0 && p.p99_us > p.limit_us ? health_style(Health::Degraded) : Style{};
  int x = in.x;
  auto say = [&](const std::string& text, Style style) {
    put(screen, in, x, in.y, text, style);
    x += static_cast<int>(text.size());
  };
  say("p50 " + ms(p.p50_us) + "  p95 " + ms(p.p95_us) + "  ", {});
  say("p99 " + ms(p.p99_us), late);
  say("  max " + ms(p.max_us) + " ms  n " + std::to_string(p.count), {});
  std::size_t first = p.bins.size(), last = 0;
  uint64_t fullest = 0;
  for (std::size_t i = 0; i < p.bins.size(); ++i)
    if (p.bins[i].count > 0) {
      first = std::min(first, i);
      last = i;
      fullest = std::max(fullest, p.bins[i].count);
    }
  if (first == p.bins.size()) return;
  const int label_w = 10, count_w = 8;
  const int bar_w = std::max(1, in.w - label_w - count_w - 2);
  int y = in.y + 1;
  // More bins than rows: the slowest are cut (the summary line has the max).
  for (std::size_t i = first; i <= last && y < in.y + in.h; ++i, ++y) {
    const auto& b = p.bins[i];
    put(screen, in, in.x, y, fit(b.label, label_w), {Color::Dim, false, false});
    put(screen, in, in.x + label_w, y, bar(static_cast<double>(b.count) / static_cast<double>(fullest), bar_w));
    put(screen, in, in.x + label_w + bar_w + 1, y, right(std::to_string(b.count), count_w));
  }
}

}  // namespace hitl::tui
