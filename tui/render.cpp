#include "tui/render.h"

#include <algorithm>

#include "tui/draw.h"
#include "tui/layout.h"
#include "tui/panels.h"

namespace hitl::tui {
namespace {

constexpr const char* kViewHints = "?:help q:quit";
constexpr const char* kScrollHint = "PgUp/PgDn:messages";

/// The keys that act, in the footer's order: the footer's word, the help's words.
struct KeyHelp {
  char key;
  const char* hint;
  const char* help;
};
constexpr KeyHelp kActionKeys[] = {
    {'a', "arm", "arm"},       {'d', "disarm", "disarm (asks first in the air)"},
    {'t', "takeoff", "take off"}, {'l', "land", "land"},
    {'p', "pause", "pause / resume"}, {'r', "reset", "reset to home (asks when armed)"},
    {'f', "fly", "fly the -t trajectory"}, {'s', "shell", "one shell command"},
    {'x', "fault", "the fault menu: start, clear"}};

/// The footer: the keys that work on this dashboard, the scroll keys while they fit, help, quit.
std::string key_hints(const std::string& keys, int width) {
  std::string acting;
  for (const auto& k : kActionKeys)
    if (keys.find(k.key) != std::string::npos) acting += std::string(1, k.key) + ":" + k.hint + " ";
  const std::string with_scroll = acting + kScrollHint + " " + kViewHints;
  return static_cast<int>(with_scroll.size()) <= width ? with_scroll : acting + kViewHints;
}

const char* const kHelpTail[] = {
    "PgUp PgDn  scroll the messages (Home oldest, End newest)",
    "",
    "Rates: green within 5 % of expected, yellow 5-20 %,",
    "red worse or stale. Test ratios: red from 1 (rejected).",
    "Without colours the words ok / warn / bad / STOP say it."};
const char* const kHelpActing[] = {
    "",
    "Keys act through the session's client port, as hitl arm,",
    "hitl fly and hitl shell do from another terminal."};

/// The help overlay's lines: the keys that work here, two a line, then what the colours mean.
std::vector<std::string> help_lines(const std::string& keys) {
  std::vector<std::string> lines;
  std::string pending;
  for (const auto& k : kActionKeys) {
    if (keys.find(k.key) == std::string::npos) continue;
    const std::string item = std::string(1, k.key) + "  " + k.help;
    if (pending.empty()) {
      pending = item;
    } else {
      lines.push_back(fit(pending, 25) + item);
      pending.clear();
    }
  }
  if (!pending.empty()) lines.push_back(pending);
  lines.push_back(fit("?  this help", 25) + "q  quit");
  for (const char* line : kHelpTail) lines.emplace_back(line);
  if (!keys.empty()) for (const char* line : kHelpActing) lines.emplace_back(line);
  lines.emplace_back("Any key closes this help.");
  return lines;
}

void draw_header(Screen& screen, const Rect& r, const DashboardModel& m) {
  int x = r.x;
  auto cell = [&](const std::string& text, Style style = {}) {
    put(screen, r, x, r.y, text, style);
    x += static_cast<int>(text.size());
  };
  cell(" " + m.title + " ", {Color::Accent, true, true});
  cell(" ");
  cell(m.state, health_style(m.state_health));
  cell("  " + m.clock);
  // Right-aligned in what is left: an action in flight, else (before any key) the two keys
  // everyone needs; the footer lists them too.
  std::string hint = !m.busy.empty() ? m.busy : m.outcome ? "" : kViewHints;
  const int room = r.x + r.w - x - 3;
  if (room < 4) return;
  if (static_cast<int>(hint.size()) > room) hint = "..." + hint.substr(hint.size() - static_cast<std::size_t>(room - 3));
  if (!hint.empty())
    put(screen, r, r.x + r.w - static_cast<int>(hint.size()) - 1, r.y, hint, m.busy.empty() ? Style{Color::Dim, false, false} : Style{Color::Accent, true, false});
  // Pinned between them: the last key's outcome, stamped like the messages, cut to the room left.
  if (!m.outcome) return;
  const int outcome_room = r.x + r.w - x - 3 - (hint.empty() ? 0 : static_cast<int>(hint.size()) + 2);
  if (outcome_room < 12) return;
  std::string text = format("%.1f ", m.outcome->t_s) + m.outcome->text;
  if (static_cast<int>(text.size()) > outcome_room) text = text.substr(0, static_cast<std::size_t>(outcome_room - 3)) + "...";
  x += 2;
  put(screen, r, x, r.y, "| ", {Color::Dim, false, false});
  put(screen, r, x + 2, r.y, text, severity_style(m.outcome->severity));
}

void draw_footer(Screen& screen, const Rect& r, const DashboardModel& m, const Interaction& in) {
  switch (in.mode) {
    case Interaction::Mode::Confirm: {
      // A question longer than the line is shown whole above it (draw_question).
      const std::string line = in.question + "  [y/N]";
      put(screen, r, r.x, r.y, fit(static_cast<int>(line.size()) <= r.w ? line : "y: yes, any other key: no  [y/N]", r.w),
          {Color::Warning, true, true});
      return;
    }
    case Interaction::Mode::Prompt: {
      const std::string line = in.label + in.input;
      // Keep the end of a long line in view (the cursor is there).
      const std::string shown = static_cast<int>(line.size()) + 2 > r.w ? line.substr(line.size() + 2 - static_cast<std::size_t>(r.w)) : line;
      put(screen, r, r.x, r.y, fit(shown + "_", r.w), {Color::Accent, true, false});
      return;
    }
    case Interaction::Mode::FaultMenu:
      put(screen, r, r.x, r.y, fit(fault_menu_hints(in.fault_menu), r.w), {Color::Accent, true, false});
      return;
    case Interaction::Mode::Normal:
    case Interaction::Mode::Help:
      put(screen, r, r.x, r.y, fit(key_hints(m.keys, r.w), r.w), {Color::Dim, false, false});
      return;
  }
}

/// A question too long for the footer, wrapped in a box just above it.
void draw_question(Screen& screen, const std::string& question) {
  const int w = std::min(screen.width(), 72);
  const auto lines = wrap(question, w - 4);
  const int h = static_cast<int>(lines.size()) + 2;
  const Rect box{(screen.width() - w) / 2, screen.height() - 1 - h, w, h};
  for (int y = box.y; y < box.y + box.h; ++y) put(screen, box, box.x, y, std::string(static_cast<std::size_t>(w), ' '));
  screen.box(box, "Confirm", {Color::Warning, true, false});
  int y = box.y + 1;
  for (const auto& line : lines) put(screen, box.inner(), box.x + 2, y++, line, {Color::Warning, true, false});
}

void draw_help(Screen& screen, const std::string& keys) {
  const auto lines = help_lines(keys);
  const int w = 64, h = static_cast<int>(lines.size()) + 2;
  const Rect box{(screen.width() - w) / 2, (screen.height() - h) / 2, w, h};
  const Rect in = box.inner();
  for (int y = box.y; y < box.y + box.h; ++y) put(screen, box, box.x, y, std::string(static_cast<std::size_t>(w), ' '));
  screen.box(box, "Keys and colours", {Color::Accent, true, false});
  int y = in.y;
  for (const auto& line : lines) put(screen, in, in.x + 1, y++, line);
}

}  // namespace

void render(Screen& screen, const DashboardModel& model, const Interaction& interaction) {
  screen.clear();
  const Layout l = layout_for(screen.width(), screen.height(), model);
  if (l.too_small) {
    const std::string text = format("terminal %dx%d: the dashboard needs %dx%d", screen.width(), screen.height(), kMinWidth, kMinHeight);
    screen.text(0, 0, text.substr(0, static_cast<std::size_t>(std::max(0, screen.width()))), {Color::Bad, true, false});
    screen.text(0, 1, std::string("q quits").substr(0, static_cast<std::size_t>(std::max(0, screen.width()))));
    screen.flush();
    return;
  }
  draw_header(screen, l.header, model);
  if (!l.paths.empty()) draw_paths(screen, l.paths, model.paths);
  if (!l.dsp_hitl.empty() && model.dsp_hitl) draw_dsp_hitl(screen, l.dsp_hitl, *model.dsp_hitl);
  if (!l.vehicle.empty() && model.vehicle) draw_vehicle(screen, l.vehicle, *model.vehicle);
  if (!l.ekf.empty() && model.ekf) draw_ekf(screen, l.ekf, *model.ekf);
  if (!l.link.empty()) draw_link(screen, l.link, model.link_partner, model.link_health, model.link);
  if (!l.latency.empty() && model.latency) draw_latency(screen, l.latency, *model.latency);
  if (!l.graphs.empty() && model.graphs) draw_graphs(screen, l.graphs, *model.graphs);
  if (!l.messages.empty()) draw_messages(screen, l.messages, model.messages, interaction.messages_top);
  draw_footer(screen, l.footer, model, interaction);
  if (interaction.mode == Interaction::Mode::Help) draw_help(screen, model.keys);
  if (interaction.mode == Interaction::Mode::FaultMenu) draw_fault_menu(screen, interaction.fault_menu, model.active_faults);
  if (interaction.mode == Interaction::Mode::Confirm && static_cast<int>(interaction.question.size()) + 7 > l.footer.w)
    draw_question(screen, interaction.question);
  screen.flush();
}

}  // namespace hitl::tui
