// `x` on the sim dashboard: the fault menu (docs/tui.md). A pick list of the active faults (Enter or
// c clears one, and "clear all") and then the whole catalogue by group (engine/faults/fault_spec.h)
// with its one-line meanings; letters typed filter it by name or group. Enter on a fault opens its
// line pre-filled with the catalogue's example (`motor:2,0.75`), its arguments' names and ranges
// shown above; Enter there starts it. `:` opens the same line empty: the typed form
// (NAME[:ARGS][+DUR], clear [NAME]). Pure: keys in, the argument of Action::Fault out (the same
// command the typed form gives); drawn from the dashboard's model, never waiting on the session.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/faults/fault_spec.h"
#include "tui/dashboard_model.h"
#include "tui/key.h"
#include "tui/screen.h"

namespace hitl::tui {

class FaultMenu {
 public:
  enum class Page { List, Line };

  /// One row of the list.
  struct Row {
    enum class Kind { Heading, Active, ClearAll, Fault, Nothing };
    Kind kind = Kind::Heading;
    std::string heading;                     ///< Heading: "Active faults (2)", "GPS"; Nothing: what to do
    const ActiveFault* active = nullptr;     ///< Active (points into the list given)
    const faults::FaultInfo* fault = nullptr;  ///< Fault
    bool selectable() const { return kind == Kind::Active || kind == Kind::ClearAll || kind == Kind::Fault; }
  };

  struct Result {
    bool close = false;                  ///< the menu is done (its command, if any, runs)
    std::optional<std::string> command;  ///< for Action::Fault: "gps-loss+10", "clear motor", "clear"
  };

  static constexpr std::size_t kMaxLineLength = 200;
  static constexpr std::size_t kMaxFilterLength = 40;

  /// One key; `active` is what the dashboard shows now (it changes while the menu is open).
  Result on_key(const Key& key, const std::vector<ActiveFault>& active);
  /// How many list rows the screen shows (the loop sets it from the screen's size before each key).
  void set_page_rows(int rows) { page_rows_ = rows > 1 ? rows : 1; }

  /// The list as drawn now: the active faults first, then each group's faults, filtered.
  std::vector<Row> rows(const std::vector<ActiveFault>& active) const;
  /// The selected row's index in rows(active) (-1 when nothing can be selected).
  int selected(const std::vector<ActiveFault>& active) const;
  /// The first row shown, with `page_rows` rows: the last one scrolled to, moved to keep the
  /// selection in view (a smaller terminal than the keys saw).
  int top(const std::vector<ActiveFault>& active, int page_rows) const;

  Page page() const { return page_; }
  const std::string& filter() const { return filter_; }
  const std::string& line() const { return line_; }
  /// The Line page's fault; nullptr for the typed form (`:`).
  const faults::FaultInfo* fault() const { return fault_; }
  /// Why Enter did not start the line (the catalogue's message), "" when nothing was refused.
  const std::string& error() const { return error_; }

 private:
  Result on_list_key(const Key& key, const std::vector<ActiveFault>& active);
  Result on_line_key(const Key& key);
  void select(const std::vector<Row>& rows, int index);
  void select_first(const std::vector<Row>& rows);
  void open_line(const faults::FaultInfo* fault);

  Page page_ = Page::List;
  std::string filter_;
  std::string selected_key_;  ///< what is selected ("active:motor:2,0.6", "clear", "fault:gps-loss"), "" the first row
  int selected_index_ = 0;    ///< where it was, when it is gone (a fault that ended)
  int top_ = 0;
  int page_rows_ = 10;
  std::string line_;
  const faults::FaultInfo* fault_ = nullptr;
  std::string error_;
};

/// Where the menu is drawn on a `width` x `height` screen (between the header and the footer) and
/// how many list rows it shows there.
Rect fault_menu_box(int width, int height);
int fault_menu_page_rows(int width, int height);

/// The menu as an overlay, over the dashboard's panels.
void draw_fault_menu(Screen& screen, const FaultMenu& menu, const std::vector<ActiveFault>& active);

/// The footer's keys while the menu is open.
std::string fault_menu_hints(const FaultMenu& menu);

}  // namespace hitl::tui
