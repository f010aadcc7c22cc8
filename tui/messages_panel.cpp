// Messages: the autopilot's STATUSTEXT and the dashboard's own events, newest at the bottom; the
// view follows the newest until scrolled back (PgUp), then stays on the same rows as lines arrive.
#include "tui/draw.h"
#include "tui/panels.h"

#include <algorithm>

namespace hitl::tui {
namespace {

struct Row {
  std::string text;
  Style style;
};

/// Every line wrapped to `width`, oldest first, stamps on the first row of each.
std::vector<Row> rows_of(const std::vector<LogLine>& lines, int width) {
  std::vector<Row> rows;
  for (const auto& line : lines) {
    const std::string stamp = format("%6.1f ", line.t_s);
    const std::string text = line.repeats > 1 ? line.text + format(" (x%d)", line.repeats) : line.text;
    auto wrapped = wrap(text, width - static_cast<int>(stamp.size()));
    if (wrapped.empty()) wrapped.emplace_back();
    for (std::size_t k = 0; k < wrapped.size(); ++k)
      rows.push_back({(k == 0 ? stamp : std::string(stamp.size(), ' ')) + wrapped[k], severity_style(line.severity)});
  }
  return rows;
}

}  // namespace

int message_row_count(const std::vector<LogLine>& lines, int width) {
  return width <= 0 ? 0 : static_cast<int>(rows_of(lines, width).size());
}

void draw_messages(Screen& screen, const Rect& r, const std::vector<LogLine>& lines, std::optional<int> top_row) {
  const Rect in = r.inner();
  if (in.empty()) {
    screen.box(r, "Messages");
    return;
  }
  const auto rows = rows_of(lines, in.w);
  const int total = static_cast<int>(rows.size());
  const int last_top = std::max(0, total - in.h);
  const int top = top_row ? std::clamp(*top_row, 0, last_top) : last_top;
  // Scrolled back: the title says where, and how to return.
  if (top_row && top < last_top)
    screen.box(r, format("Messages %d-%d/%d, End: newest", top + 1, std::min(total, top + in.h), total),
               {Color::Warning, false, false});
  else
    screen.box(r, "Messages");
  for (int k = 0; k < in.h && top + k < total; ++k) {
    const Row& row = rows[static_cast<std::size_t>(top + k)];
    put(screen, in, in.x, in.y + k, row.text, row.style);
  }
}

}  // namespace hitl::tui
