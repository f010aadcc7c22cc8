#include "tui/dashboard.h"

#include <algorithm>
#include <csignal>
#include <cstring>

#include "base/common/clock.h"
#include "tui/fault_menu.h"
#include "tui/keys.h"
#include "tui/layout.h"
#include "tui/panels.h"
#include "tui/render.h"
#include "tui/terminal.h"

namespace hitl::tui {

Expected<DashboardEnd> run_dashboard(DashboardSource& source, DashboardActions* actions, const DashboardOptions& options) {
  auto terminal = Terminal::open();
  if (!terminal) return terminal.error();
  NcursesScreen& screen = (*terminal)->screen();
  Dispatcher dispatcher;
  DashboardEnd end;
  double render_total_ms = 0;
  const double period_s = 1.0 / std::max(1.0, options.refresh_hz);
  for (;;) {
    if (const int sig = (*terminal)->stop_signal()) {
      end.reason = DashboardEnd::Reason::Signal;
      end.detail = strsignal(sig);
      break;
    }
    if (auto why = source.finished()) {
      end.reason = DashboardEnd::Reason::SourceFinished;
      end.detail = *why;
      break;
    }
    const DashboardModel model = source.collect();
    const double t0 = monotonic_s();
    render(screen, model, dispatcher.interaction());
    const double ms = (monotonic_s() - t0) * 1000.0;
    render_total_ms += ms;
    end.render_ms_max = std::max(end.render_ms_max, ms);
    ++end.frames;
    // Keys until the next frame is due; any key that changes something redraws at once.
    const double next_s = t0 + period_s;
    bool quit = false, redraw = false;
    while (!quit && !redraw) {
      const double left_s = next_s - monotonic_s();
      if (left_s <= 0) break;
      const Key key = screen.read_key(static_cast<int>(left_s * 1000) + 1);
      if (key.kind == Key::Kind::None) {
        if ((*terminal)->stop_signal()) break;
        continue;
      }
      const Rect messages = layout_for(screen.width(), screen.height(), model).messages.inner();
      dispatcher.set_messages_view(message_row_count(model.messages, messages.w), messages.h);
      dispatcher.set_fault_menu_rows(fault_menu_page_rows(screen.width(), screen.height()));
      const auto result = dispatcher.on_key(key, model, actions);
      if (result.note) source.note(Severity::Notice, *result.note);
      quit = result.quit;
      redraw = true;
    }
    if (quit) break;
  }
  end.render_ms_mean = end.frames ? render_total_ms / static_cast<double>(end.frames) : 0;
  return end;
}

}  // namespace hitl::tui
