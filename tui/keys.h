// The keyboard: raw input decoded to keys once (the screen does it), then one dispatcher that
// turns keys into actions (btop's Input::get / Input::process). The dispatcher holds what the
// keyboard is in the middle of: the help overlay, a confirmation (disarm in the air, reset while
// armed, stopping a trajectory), the one-line shell prompt or the fault menu (fault_menu.h).
#pragma once

#include <optional>
#include <string>

#include "tui/actions.h"
#include "tui/dashboard_model.h"
#include "tui/key.h"
#include "tui/render.h"

namespace hitl::tui {

class Dispatcher {
 public:
  struct Result {
    bool quit = false;
    std::optional<std::string> note;  ///< for the messages panel (a refusal, a cancelled question)
  };

  /// One key, in the state of `model` (in air? a trajectory running?). `actions` may be null
  /// (a dashboard that only shows): then every action key says so.
  Result on_key(const Key& key, const DashboardModel& model, DashboardActions* actions);
  const Interaction& interaction() const { return interaction_; }
  /// The messages panel as drawn now: rows in all, rows shown (the loop sets it before each key).
  void set_messages_view(int total_rows, int page_rows);
  /// The fault menu's list rows on the screen now (the loop sets it before each key).
  void set_fault_menu_rows(int rows) { interaction_.fault_menu.set_page_rows(rows); }

  static constexpr std::size_t kMaxCommandLength = 200;

 private:
  Result request(Action action, const DashboardModel& model, DashboardActions* actions);
  Result start(Action action, const std::string& argument, DashboardActions* actions);
  /// PgUp, PgDn, Home, End on the messages panel; false for other keys.
  bool scroll(const Key& key);
  /// Enters `mode`; the messages panel stays where it was scrolled.
  void enter(Interaction::Mode mode, std::string question = {}, std::string label = {});

  Interaction interaction_;
  std::optional<Action> pending_;  ///< what y confirms
  int message_rows_ = 0, message_page_ = 0;
};

}  // namespace hitl::tui
