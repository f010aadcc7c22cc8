#include "tui/fault_menu.h"

#include <algorithm>
#include <cctype>

#include "tui/draw.h"

namespace hitl::tui {
namespace {

constexpr int kMaxMenuWidth = 100;
constexpr int kNameColumn = 16;        ///< the longest name (actuators-stale) and a space
constexpr int kDetailRows = 2;         ///< under the list: the selected row in full
constexpr int kMeaningRows = 3;        ///< the Line page's meaning, wrapped

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool contains(const std::string& haystack, const std::string& needle) { return lower(haystack).find(lower(needle)) != std::string::npos; }

/// "Vehicle", "IMU", "HIL link": the group's name as a heading.
std::string heading(faults::FaultGroup g) {
  std::string s = faults::to_string(g);
  if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return s;
}

std::string key_of(const FaultMenu::Row& r) {
  switch (r.kind) {
    case FaultMenu::Row::Kind::Active: return "active:" + r.active->text;
    case FaultMenu::Row::Kind::ClearAll: return "clear";
    case FaultMenu::Row::Kind::Fault: return std::string("fault:") + r.fault->name;
    default: return "";
  }
}

/// The nearest selectable row from `index` in direction `step` (+1 or -1), else the other way; -1 for none.
int nearest_selectable(const std::vector<FaultMenu::Row>& rows, int index, int step) {
  const int n = static_cast<int>(rows.size());
  if (n == 0) return -1;
  index = std::clamp(index, 0, n - 1);
  for (int i = index; i >= 0 && i < n; i += step)
    if (rows[static_cast<std::size_t>(i)].selectable()) return i;
  for (int i = index; i >= 0 && i < n; i -= step)
    if (rows[static_cast<std::size_t>(i)].selectable()) return i;
  return -1;
}

std::string compact(double v) { return format("%g", v); }

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(' ') - first + 1);
}

/// `text` cut to `width` with "..." when longer.
std::string ellipsis(const std::string& text, int width) {
  if (width <= 0) return "";
  if (static_cast<int>(text.size()) <= width) return text;
  if (width <= 3) return text.substr(0, static_cast<std::size_t>(width));
  return text.substr(0, static_cast<std::size_t>(width - 3)) + "...";
}

}  // namespace

std::vector<FaultMenu::Row> FaultMenu::rows(const std::vector<ActiveFault>& active) const {
  std::vector<Row> out;
  auto fault_matches = [&](const faults::FaultInfo& f) {
    return filter_.empty() || contains(f.name, filter_) || contains(faults::to_string(f.group), filter_);
  };
  std::vector<const ActiveFault*> shown;
  for (const auto& a : active) {
    const auto* f = faults::find_fault(a.name);
    if (filter_.empty() || contains(a.text, filter_) || (f != nullptr && fault_matches(*f))) shown.push_back(&a);
  }
  if (!shown.empty()) {
    out.push_back({Row::Kind::Heading, format("Active faults (%zu)", shown.size())});
    for (const auto* a : shown) out.push_back({Row::Kind::Active, "", a});
    if (filter_.empty()) out.push_back({Row::Kind::ClearAll});
  }
  for (const auto g : faults::kFaultGroups) {
    bool headed = false;
    for (const auto& f : faults::fault_catalogue()) {
      if (f.group != g || !fault_matches(f)) continue;
      if (!headed) out.push_back({Row::Kind::Heading, heading(g)});
      headed = true;
      out.push_back({Row::Kind::Fault, "", nullptr, &f});
    }
  }
  if (out.empty()) out.push_back({Row::Kind::Nothing, "no fault matches '" + filter_ + "': Backspace edits the filter, : types a fault"});
  return out;
}

int FaultMenu::selected(const std::vector<ActiveFault>& active) const {
  const auto list = rows(active);
  if (!selected_key_.empty())
    for (std::size_t i = 0; i < list.size(); ++i)
      if (key_of(list[i]) == selected_key_) return static_cast<int>(i);
  return nearest_selectable(list, selected_key_.empty() ? 0 : selected_index_, +1);
}

int FaultMenu::top(const std::vector<ActiveFault>& active, int page_rows) const {
  const int n = static_cast<int>(rows(active).size());
  const int sel = selected(active);
  int t = top_;
  if (sel >= 0 && sel < t) t = sel;
  if (sel >= 0 && sel >= t + page_rows) t = sel - page_rows + 1;
  return std::clamp(t, 0, std::max(0, n - page_rows));
}

void FaultMenu::select(const std::vector<Row>& list, int index) {
  if (index < 0 || index >= static_cast<int>(list.size())) return;
  selected_key_ = key_of(list[static_cast<std::size_t>(index)]);
  selected_index_ = index;
  // Keep it in view, with the heading above it when that is where it starts.
  const int first = index > 0 && list[static_cast<std::size_t>(index - 1)].kind == Row::Kind::Heading ? index - 1 : index;
  if (first < top_) top_ = first;
  if (index >= top_ + page_rows_) top_ = index - page_rows_ + 1;
  top_ = std::clamp(top_, 0, std::max(0, static_cast<int>(list.size()) - page_rows_));
}

void FaultMenu::select_first(const std::vector<Row>& list) {
  top_ = 0;
  selected_key_.clear();
  selected_index_ = 0;
  select(list, nearest_selectable(list, 0, +1));
}

void FaultMenu::open_line(const faults::FaultInfo* fault) {
  page_ = Page::Line;
  fault_ = fault;
  line_ = fault != nullptr ? std::string(fault->name) + fault->example : "";
  error_.clear();
}

FaultMenu::Result FaultMenu::on_key(const Key& key, const std::vector<ActiveFault>& active) {
  if (key.kind == Key::Kind::None || key.kind == Key::Kind::Resize) return {};
  return page_ == Page::List ? on_list_key(key, active) : on_line_key(key);
}

FaultMenu::Result FaultMenu::on_list_key(const Key& key, const std::vector<ActiveFault>& active) {
  const auto list = rows(active);
  const int n = static_cast<int>(list.size());
  const int sel = selected(active);
  const Row* row = sel >= 0 ? &list[static_cast<std::size_t>(sel)] : nullptr;
  auto clear = [&]() -> Result {
    if (row == nullptr) return {};
    if (row->kind == Row::Kind::Active) return {true, "clear " + row->active->name};
    if (row->kind == Row::Kind::ClearAll) return {true, std::string("clear")};
    return {};
  };
  const int page = std::max(1, page_rows_ - 1);
  switch (key.kind) {
    case Key::Kind::Escape: return {true, std::nullopt};
    case Key::Kind::Up:
      if (sel > 0) select(list, nearest_selectable(list, sel - 1, -1));  // at the first: its heading comes into view
      return {};
    case Key::Kind::Down: select(list, nearest_selectable(list, sel + 1, +1)); return {};
    case Key::Kind::PageUp: select(list, nearest_selectable(list, std::max(0, sel - page), -1)); return {};
    case Key::Kind::PageDown: select(list, nearest_selectable(list, std::min(n - 1, sel + page), +1)); return {};
    case Key::Kind::Home: select_first(list); return {};
    case Key::Kind::End: select(list, nearest_selectable(list, n - 1, -1)); return {};
    case Key::Kind::Enter:
      if (row != nullptr && row->kind == Row::Kind::Fault) {
        open_line(row->fault);
        return {};
      }
      return clear();
    case Key::Kind::Backspace:
      if (filter_.empty()) return {};
      filter_.pop_back();
      select_first(rows(active));
      return {};
    case Key::Kind::Char: break;
    default: return {};
  }
  const char c = key.ch;
  if (c == ':') {
    open_line(nullptr);
    return {};
  }
  if (c == 'c' && filter_.empty() && row != nullptr && row->kind != Row::Kind::Fault) return clear();
  if ((std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == ' ') && filter_.size() < kMaxFilterLength) {
    if (c == ' ' && filter_.empty()) return {};
    filter_ += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    select_first(rows(active));
  }
  return {};
}

FaultMenu::Result FaultMenu::on_line_key(const Key& key) {
  switch (key.kind) {
    case Key::Kind::Escape:
      page_ = Page::List;
      error_.clear();
      return {};
    case Key::Kind::Backspace:
      if (!line_.empty()) line_.pop_back();
      error_.clear();
      return {};
    case Key::Kind::Char:
      if (line_.size() < kMaxLineLength) line_ += key.ch;
      error_.clear();
      return {};
    case Key::Kind::Enter: {
      const std::string text = trimmed(line_);
      if (text.empty()) {
        error_ = "type a fault: NAME[:ARGS][+DUR], or clear [NAME]";
        return {};
      }
      if (text == "clear" || text.rfind("clear ", 0) == 0) return {true, text};
      // Checked here so that a mistake stays on the line to fix; the dashboard parses it again.
      if (auto spec = faults::parse_live_fault(text); !spec) {
        error_ = spec.error().message;
        return {};
      }
      return {true, text};
    }
    default: return {};
  }
}

Rect fault_menu_box(int width, int height) {
  const int w = std::min(width, kMaxMenuWidth);
  return {(width - w) / 2, 1, w, height - 2};  // between the header and the footer
}

int fault_menu_page_rows(int width, int height) {
  return std::max(1, fault_menu_box(width, height).inner().h - 1 - kDetailRows);  // the filter line, the detail
}

namespace {

constexpr Style kHeadingStyle{Color::Accent, true, false};
constexpr Style kDimStyle{Color::Dim, false, false};
constexpr Style kErrorStyle{Color::Bad, true, false};

/// "gps-loss        since 10.0 s, 5.0 s left": the name in a column of `column` where it fits.
std::string active_line(const ActiveFault& a, int column) {
  const std::string name = static_cast<int>(a.text.size()) < column ? fit(a.text, column) : a.text + " ";
  return name + "since " + format("%.1f s", a.started_s) + (a.left_s ? format(", %.1f s left", *a.left_s) : ", until cleared");
}

void draw_list(Screen& screen, const Rect& in, const FaultMenu& menu, const std::vector<ActiveFault>& active) {
  const auto list = menu.rows(active);
  const int page = std::max(1, in.h - 1 - kDetailRows);
  const int sel = menu.selected(active);
  const int top = menu.top(active, page);
  // The filter line, and where the selection is among the rows that can be picked.
  int position = 0, selectable = 0;
  for (int i = 0; i < static_cast<int>(list.size()); ++i)
    if (list[static_cast<std::size_t>(i)].selectable()) {
      ++selectable;
      if (i <= sel) position = selectable;
    }
  const std::string where = format("%d/%d", position, selectable);
  if (menu.filter().empty())
    put(screen, in, in.x + 1, in.y, "type to filter by name or group; : types a fault", kDimStyle);
  else
    put(screen, in, in.x + 1, in.y, "filter: " + menu.filter() + "_", kHeadingStyle);
  put(screen, in, in.x + in.w - static_cast<int>(where.size()) - 1, in.y, where, kDimStyle);

  for (int r = 0; r < page && top + r < static_cast<int>(list.size()); ++r) {
    const int i = top + r;
    const auto& row = list[static_cast<std::size_t>(i)];
    const int y = in.y + 1 + r;
    const bool chosen = i == sel;
    std::string text;
    Style style;
    switch (row.kind) {
      case FaultMenu::Row::Kind::Heading: put(screen, in, in.x + 1, y, row.heading, kHeadingStyle); continue;
      case FaultMenu::Row::Kind::Nothing: put(screen, in, in.x + 1, y, row.heading, kDimStyle); continue;
      case FaultMenu::Row::Kind::Active:
        text = "  " + active_line(*row.active, kNameColumn);
        style = {Color::Warning, false, false};
        break;
      case FaultMenu::Row::Kind::ClearAll: text = "  clear all"; break;
      case FaultMenu::Row::Kind::Fault:
        text = "  " + fit(row.fault->name, kNameColumn) + row.fault->meaning;
        break;
    }
    if (chosen) style.reverse = true;
    put(screen, in, in.x, y, fit(ellipsis(text, in.w - 1), in.w - 1), style);  // the last column: the scroll marks
  }
  if (top > 0) put(screen, in, in.x + in.w - 1, in.y + 1, "^", kDimStyle);
  if (top + page < static_cast<int>(list.size())) put(screen, in, in.x + in.w - 1, in.y + page, "v", kDimStyle);

  // The selected row in full: a fault's usage and meaning, or what clearing does.
  std::string detail;
  if (sel >= 0) {
    const auto& row = list[static_cast<std::size_t>(sel)];
    if (row.kind == FaultMenu::Row::Kind::Fault)
      detail = faults::usage(*row.fault) + " - " + row.fault->meaning;
    else if (row.kind == FaultMenu::Row::Kind::Active)
      detail = "Enter or c ends every active " + row.active->name + " now (clear " + row.active->name + ").";
    else if (row.kind == FaultMenu::Row::Kind::ClearAll)
      detail = "Enter or c ends every active fault now (clear).";
  }
  const auto lines = wrap(detail, in.w - 2);
  for (int k = 0; k < kDetailRows && k < static_cast<int>(lines.size()); ++k)
    put(screen, in, in.x + 1, in.y + in.h - kDetailRows + k, lines[static_cast<std::size_t>(k)], kDimStyle);
}

void draw_line_page(Screen& screen, const Rect& in, const FaultMenu& menu) {
  const faults::FaultInfo* f = menu.fault();
  int y = in.y;
  const int w = in.w - 2;
  auto say = [&](const std::string& text, Style style = {}) {
    for (const auto& l : wrap(text, w)) {
      if (y >= in.y + in.h) return;
      put(screen, in, in.x + 1, y++, l, style);
    }
  };
  if (f != nullptr) {
    say(std::string("Start ") + f->name + " (" + faults::to_string(f->group) + ")", kHeadingStyle);
    const auto meaning = wrap(f->meaning, w);
    for (int k = 0; k < kMeaningRows && k < static_cast<int>(meaning.size()); ++k) put(screen, in, in.x + 1, y++, meaning[static_cast<std::size_t>(k)]);
    ++y;
    say("Arguments, in this order after the ':'", kHeadingStyle);
    if (f->args.empty()) say("  none");
    for (std::size_t i = 0; i < f->args.size() && y < in.y + in.h; ++i) {
      const auto& a = f->args[i];
      put(screen, in, in.x + 1, y++, "  " + fit(a.name, 12) + compact(a.min) + " .. " + compact(a.max) + (a.integer ? ", whole" : "") +
          (i >= f->required_args ? ", optional" : ""));
    }
    ++y;
    say(f->needs_duration ? "+SECONDS: its duration, needed (its shape spans it)."
                          : "+SECONDS at the end: its duration; without it, it lasts until cleared.",
        kDimStyle);
  } else {
    say("Type a fault", kHeadingStyle);
    say("NAME[:ARGS][+DUR] starts it now (gps-loss+10, motor:2,0.6); clear NAME ends the active faults of that "
        "name, clear ends all (docs/faults.md).");
  }
  ++y;
  // The line, its end kept in view (the cursor is there).
  const std::string shown = "> " + menu.line() + "_";
  const std::string cut = static_cast<int>(shown.size()) > w ? shown.substr(shown.size() - static_cast<std::size_t>(w)) : shown;
  if (y < in.y + in.h) put(screen, in, in.x + 1, y++, cut, {Color::Accent, true, false});
  if (!menu.error().empty()) say(menu.error(), kErrorStyle);
}

}  // namespace

void draw_fault_menu(Screen& screen, const FaultMenu& menu, const std::vector<ActiveFault>& active) {
  const Rect box = fault_menu_box(screen.width(), screen.height());
  if (box.w < 20 || box.h < 6) return;
  for (int y = box.y; y < box.y + box.h; ++y) put(screen, box, box.x, y, std::string(static_cast<std::size_t>(box.w), ' '));
  screen.box(box, menu.page() == FaultMenu::Page::List ? "Faults: start or clear" : "Faults: start one now", kHeadingStyle);
  const Rect in = box.inner();
  if (menu.page() == FaultMenu::Page::List) draw_list(screen, in, menu, active);
  else draw_line_page(screen, in, menu);
}

std::string fault_menu_hints(const FaultMenu& menu) {
  if (menu.page() == FaultMenu::Page::Line) return "Enter:start now  Backspace:edit  Esc:back to the list";
  return "Up/Down PgUp/PgDn:move  Enter:pick  c:clear  letters:filter  ::type  Esc:close";
}

}  // namespace hitl::tui
