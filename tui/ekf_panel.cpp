// EKF: ESTIMATOR_STATUS flags in words, test ratios as bars, and the estimate against the
// simulator's ground truth.
#include <algorithm>
#include <cmath>
#include <vector>

#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {
namespace {

/// A test ratio passes below 1: green below 0.5, yellow up to 1, red from 1 (rejected).
Health ratio_health(double value) {
  if (!std::isfinite(value) || value >= 1.0) return Health::Bad;
  return value < 0.5 ? Health::Good : Health::Degraded;
}

}  // namespace

void draw_ekf(Screen& screen, const Rect& r, const EkfPanel& panel) {
  screen.box(r, "EKF (ESTIMATOR_STATUS)");
  const Rect in = r.inner();
  if (in.empty()) return;
  if (panel.unavailable) return draw_unavailable(screen, in, *panel.unavailable);
  int y = in.y;
  const int bottom = in.y + in.h;

  // Flags: the set ones in words, faults first (red); the lines left for ratios and the truth
  // decide how many fit, the rest is counted ("+3").
  const int ratio_lines = in.w >= 80 ? 1 : 2;
  const int flag_lines = std::max(1, in.h - ratio_lines - 1 - (in.h >= 6 ? 1 : 0));
  {
    std::vector<const telemetry::EstimatorFlag*> set;
    for (const auto& f : panel.flags)
      if (f.set && f.fault) set.push_back(&f);
    for (const auto& f : panel.flags)
      if (f.set && !f.fault) set.push_back(&f);
    int x = in.x, line = 0;
    for (std::size_t i = 0; i < set.size(); ++i) {
      const std::string word = set[i]->word;
      const bool last_line = line == flag_lines - 1;
      const int room = in.x + in.w - x - (last_line && i + 1 < set.size() ? 4 : 0);  // keep room for "+N"
      if (static_cast<int>(word.size()) > room) {
        if (last_line) {
          put(screen, in, x, y, format("+%zu", set.size() - i), {Color::Dim, false, false});
          break;
        }
        ++line;
        ++y;
        x = in.x;
      }
      put(screen, in, x, y, word, set[i]->fault ? health_style(Health::Bad) : Style{Color::Good, false, false});
      x += static_cast<int>(word.size()) + 1;
    }
    if (set.empty()) put(screen, in, in.x, y, panel.flags.empty() ? "no ESTIMATOR_STATUS yet" : "no valid estimate", health_style(Health::Bad));
    y = in.y + line + 1;
  }

  // Test ratios as bars: four a line when wide, else two.
  const int per_line = in.w >= 80 ? 4 : 2;
  const int cell_w = in.w / per_line;
  const int bar_w = std::max(3, cell_w - 6 - 5 - 1);
  for (std::size_t i = 0; i < panel.ratios.size() && y < bottom; ++i) {
    const auto& t = panel.ratios[i];
    const int x = in.x + static_cast<int>(i % static_cast<std::size_t>(per_line)) * cell_w;
    put(screen, in, x, y, fit(t.name, 6), {Color::Dim, false, false});
    put(screen, in, x + 6, y, bar(t.value, bar_w), health_style(ratio_health(t.value)));
    put(screen, in, x + 6 + bar_w, y, right(number(t.value, 2), 5), health_style(ratio_health(t.value)));
    if (i % static_cast<std::size_t>(per_line) == static_cast<std::size_t>(per_line - 1) || i + 1 == panel.ratios.size()) ++y;
  }

  // The estimate against the truth.
  if (y < bottom) {
    std::string line;
    if (panel.horizontal_error_m || panel.attitude_error_deg) {
      line = "vs truth " + number(panel.horizontal_error_m, 2) + " m h";
      if (panel.vertical_error_m) line += ", " + format("%+.2f", *panel.vertical_error_m) + " m v";
      line += ", " + number(panel.attitude_error_deg, 1) + " deg";
    } else {
      line = "vs truth: " + (panel.error_note.empty() ? std::string("waiting for estimate and truth") : panel.error_note);
    }
    put(screen, in, in.x, y++, line);
  }
  if (y < bottom && (panel.horizontal_rms_m || panel.horizontal_accuracy_m)) {
    std::string line;
    if (panel.horizontal_rms_m) line += "rms " + number(panel.horizontal_rms_m, 2) + " m, " + number(panel.attitude_rms_deg, 1) + " deg  ";
    if (panel.horizontal_accuracy_m)
      line += "own 1-sigma " + number(panel.horizontal_accuracy_m, 2) + " m h " + number(panel.vertical_accuracy_m, 2) + " m v";
    put(screen, in, in.x, y++, line, {Color::Dim, false, false});
  }
}

}  // namespace hitl::tui
