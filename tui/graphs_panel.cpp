// Graphs: the sim's last 60 s as rolling graphs (graph.h): altitude truth and estimate together,
// the tracking error while a trajectory flies, and a one-row graph per data path of its rate
// against the expected rate. Braille or ASCII as the screen says.
#include <cmath>

#include "tui/draw.h"
#include "tui/graph.h"
#include "tui/panels.h"

namespace hitl::tui {
namespace {

constexpr Style kTruthStyle{Color::Accent, false, false};
constexpr Style kEstimateStyle{Color::Good, false, false};
constexpr Style kLabelStyle{Color::Dim, false, false};
constexpr int kRateLabelW = 9;   ///< "IMU      "
constexpr int kRateValueW = 18;  ///< " 249.9/250.0 Hz"

/// The last finite sample.
std::optional<double> last(const std::vector<double>& v) {
  for (auto it = v.rbegin(); it != v.rend(); ++it)
    if (std::isfinite(*it)) return *it;
  return std::nullopt;
}

void draw_cells(Screen& screen, const Rect& in, int x, int y, const std::vector<std::u32string>& rows,
                const std::vector<std::u32string>& top, Style bottom_style, Style top_style) {
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      const char32_t ch = rows[r][c];
      if (ch == U' ') continue;
      const int cx = x + static_cast<int>(c), cy = y + static_cast<int>(r);
      if (cx < in.x || cx >= in.x + in.w || cy < in.y || cy >= in.y + in.h) continue;
      const bool from_top = r < top.size() && c < top[r].size() && top[r][c] != U' ';
      screen.glyph(cx, cy, ch, from_top ? top_style : bottom_style);
    }
}

/// A labelled graph of one or two series sharing a range: a label row, then `rows` graph rows.
void draw_graph(Screen& screen, const Rect& in, int y, int rows, const std::string& label, const std::vector<double>& a,
                const std::vector<double>* b, std::size_t capacity, double min_span, bool from_zero) {
  auto [lo, hi] = range_of(b ? std::vector<std::vector<double>>{a, *b} : std::vector<std::vector<double>>{a}, min_span);
  if (from_zero) lo = std::min(lo, 0.0), hi = std::max(hi, lo + min_span);
  put(screen, in, in.x, y, fit(label + format("   %.1f .. %.1f", lo, hi), in.w), kLabelStyle);
  const GraphSymbols symbols = screen.graph_symbols();
  auto cells = plot(a, capacity, in.w, rows, lo, hi, symbols);
  std::vector<std::u32string> top;
  if (b) {
    top = plot(*b, capacity, in.w, rows, lo, hi, symbols);
    overlay(cells, top);
  }
  draw_cells(screen, in, in.x, y + 1, cells, top, kTruthStyle, kEstimateStyle);
}

}  // namespace

void draw_graphs(Screen& screen, const Rect& r, const GraphsPanel& panel) {
  screen.box(r, format("Graphs, last %.0f s simulated", panel.window_s));
  const Rect in = r.inner();
  if (in.empty() || in.w < kRateLabelW + kRateValueW + 10) return;
  const bool tracking = !panel.tracking_error_m.empty();
  const int rate_rows = std::min(in.h, 1 + static_cast<int>(panel.rates.size()));
  const int sections = tracking ? 2 : 1;
  const int per_section = (in.h - rate_rows) / sections;
  int y = in.y;
  if (per_section >= 3) {
    const auto truth = last(panel.truth_altitude_m), estimate = last(panel.estimate_altitude_m);
    draw_graph(screen, in, y, per_section - 1,
               "Altitude m: truth " + number(truth, 1) + " (cyan), estimate " + number(estimate, 1) + " (green)",
               panel.truth_altitude_m, &panel.estimate_altitude_m, panel.capacity, 1.0, false);
    y += per_section;
    if (tracking) {
      draw_graph(screen, in, y, per_section - 1, "Tracking error m: now " + number(last(panel.tracking_error_m), 2),
                 panel.tracking_error_m, nullptr, panel.capacity, 0.5, true);
      y += per_section;
    }
  }
  y = in.y + in.h - rate_rows;
  put(screen, in, in.x, y++, fit("Rates Hz (top of each row: 125 % of expected)", in.w), kLabelStyle);
  const int graph_w = in.w - kRateLabelW - kRateValueW;
  for (const auto& rate_graph : panel.rates) {
    if (y >= in.y + in.h) break;
    const auto now = last(rate_graph.rate_hz);
    double hi = rate_graph.expected_hz * 1.25;
    if (hi <= 0) hi = std::max(1.0, range_of({rate_graph.rate_hz}, 1.0).second * 1.1);
    const auto cells = plot(rate_graph.rate_hz, panel.capacity, graph_w, 1, 0.0, hi, screen.graph_symbols());
    put(screen, in, in.x, y, fit(rate_graph.name, kRateLabelW - 1), kLabelStyle);
    const bool off = now && rate_graph.expected_hz > 0 && std::abs(*now / rate_graph.expected_hz - 1.0) > 0.05;
    draw_cells(screen, in, in.x + kRateLabelW, y, cells, {}, off ? Style{Color::Warning, false, false} : kEstimateStyle, {});
    const std::string value = (now ? rate(*now) : std::string("n/a")) +
                              (rate_graph.expected_hz > 0 ? "/" + rate(rate_graph.expected_hz) : std::string()) + " Hz";
    put(screen, in, in.x + kRateLabelW + graph_w + 1, y, fit(value, kRateValueW - 1));
    ++y;
  }
}

}  // namespace hitl::tui
