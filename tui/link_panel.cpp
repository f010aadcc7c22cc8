// Link: the partner and the counters of the link, label and value, two or three a line.
#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {

void draw_link(Screen& screen, const Rect& r, const std::string& partner, Health health, const std::vector<LinkField>& fields) {
  screen.box(r, partner.empty() ? "Link" : "Link " + partner, health == Health::Good ? Style{} : health_style(health));
  const Rect in = r.inner();
  if (in.empty()) return;
  const int per_line = in.w >= 3 * 26 ? 3 : 2;
  const int cell_w = in.w / per_line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const int x = in.x + static_cast<int>(i % static_cast<std::size_t>(per_line)) * cell_w;
    const int y = in.y + static_cast<int>(i / static_cast<std::size_t>(per_line));
    const auto& f = fields[i];
    const int label_w = std::min<int>(static_cast<int>(f.label.size()) + 1, cell_w / 2);
    put(screen, in, x, y, fit(f.label, label_w), {Color::Dim, false, false});
    put(screen, in, x + label_w, y, fit(f.value, cell_w - label_w - 1),
        f.health == Health::Good ? Style{} : health_style(f.health));
  }
}

}  // namespace hitl::tui
