// Messages: the autopilot's STATUSTEXT and the dashboard's own events, newest at the bottom.
#include "tui/draw.h"
#include "tui/panels.h"

namespace hitl::tui {
namespace {

Style severity_style(Severity s) {
  switch (s) {
    case Severity::Info: return {};
    case Severity::Notice: return {Color::Accent, false, false};
    case Severity::Warning: return health_style(Health::Degraded);
    case Severity::Error: return health_style(Health::Bad);
  }
  return {};
}

}  // namespace

void draw_messages(Screen& screen, const Rect& r, const std::vector<LogLine>& lines) {
  screen.box(r, "Messages");
  const Rect in = r.inner();
  if (in.empty()) return;
  // Wrap the newest lines until the panel is full, then draw them oldest first.
  std::vector<std::pair<std::string, Style>> shown;
  for (auto it = lines.rbegin(); it != lines.rend() && static_cast<int>(shown.size()) < in.h; ++it) {
    const std::string stamp = format("%6.1f ", it->t_s);
    const std::string text = it->repeats > 1 ? it->text + format(" (x%d)", it->repeats) : it->text;
    auto wrapped = wrap(text, in.w - static_cast<int>(stamp.size()));
    if (wrapped.empty()) wrapped.emplace_back();
    for (std::size_t k = wrapped.size(); k-- > 0 && static_cast<int>(shown.size()) < in.h;)
      shown.emplace_back((k == 0 ? stamp : std::string(stamp.size(), ' ')) + wrapped[k], severity_style(it->severity));
  }
  int y = in.y + in.h - static_cast<int>(shown.size());
  for (auto it = shown.rbegin(); it != shown.rend(); ++it) put(screen, in, in.x, y++, it->first, it->second);
}

}  // namespace hitl::tui
