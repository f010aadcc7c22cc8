// One whole frame: header, the panels where the layout puts them, the footer (key hints, or the
// question or prompt being answered), and the help overlay. Composed on the screen, flushed once.
#pragma once

#include <optional>
#include <string>

#include "tui/dashboard_model.h"
#include "tui/fault_menu.h"
#include "tui/screen.h"

namespace hitl::tui {

/// What the keyboard is in the middle of (keys.h drives it).
struct Interaction {
  enum class Mode { Normal, Help, Confirm, Prompt, FaultMenu };
  Mode mode = Mode::Normal;
  std::string question;  ///< Confirm: what y will do
  std::string label;     ///< Prompt: "shell> "
  std::string input;     ///< Prompt: typed so far
  std::optional<int> messages_top;  ///< the messages panel scrolled back: its first row; nullopt follows the newest
  FaultMenu fault_menu;  ///< FaultMenu: the fault menu's state (`x` on the sim dashboard)
};

void render(Screen& screen, const DashboardModel& model, const Interaction& interaction);

}  // namespace hitl::tui
