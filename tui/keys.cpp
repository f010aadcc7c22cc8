#include "tui/keys.h"

#include <algorithm>

namespace hitl::tui {

const char* to_string(Action action) {
  switch (action) {
    case Action::Arm: return "arm";
    case Action::Disarm: return "disarm";
    case Action::ForceDisarm: return "force disarm";
    case Action::Takeoff: return "takeoff";
    case Action::Land: return "land";
    case Action::TogglePause: return "pause/resume";
    case Action::ResetHome: return "reset to home";
    case Action::FlyTrajectory: return "fly trajectory";
    case Action::StopTrajectory: return "stop trajectory";
    case Action::Shell: return "shell";
    case Action::Fault: return "fault";
  }
  return "?";
}

void Dispatcher::enter(Interaction::Mode mode, std::string question, std::string label) {
  const auto top = interaction_.messages_top;
  interaction_ = {mode, std::move(question), std::move(label), "", top};
}

void Dispatcher::set_messages_view(int total_rows, int page_rows) {
  message_rows_ = std::max(0, total_rows);
  message_page_ = std::max(1, page_rows);
}

bool Dispatcher::scroll(const Key& key) {
  const int last_top = std::max(0, message_rows_ - message_page_);
  const int step = std::max(1, message_page_ - 1);  // a page, one row kept for context
  auto& top = interaction_.messages_top;
  switch (key.kind) {
    case Key::Kind::PageUp: top = std::max(0, std::min(top.value_or(last_top), last_top) - step); break;
    case Key::Kind::PageDown:
      if (top) top = *top + step;
      break;
    case Key::Kind::Home: top = 0; break;
    case Key::Kind::End: top.reset(); break;
    default: return false;
  }
  if (top && *top >= last_top) top.reset();  // at the newest again: follow it
  return true;
}

Dispatcher::Result Dispatcher::start(Action action, const std::string& argument, DashboardActions* actions) {
  if (actions == nullptr) return {false, std::string(to_string(action)) + ": this dashboard only shows (no vehicle to act on)"};
  if (auto why = actions->refusal(action)) return {false, std::string(to_string(action)) + ": " + *why};
  actions->perform(action, argument);
  return {};
}

Dispatcher::Result Dispatcher::request(Action action, const DashboardModel& model, DashboardActions* actions) {
  auto confirm = [&](Action confirmed, std::string question) {
    if (actions == nullptr || actions->refusal(confirmed)) return start(confirmed, "", actions);  // says why not
    enter(Interaction::Mode::Confirm, std::move(question));
    pending_ = confirmed;
    return Result{};
  };
  const bool in_air = model.vehicle && model.vehicle->in_air;
  const bool armed = model.vehicle && model.vehicle->armed;
  switch (action) {
    case Action::Disarm:
      if (in_air) return confirm(Action::ForceDisarm, "Disarm IN THE AIR? The motors stop and the vehicle falls (forced disarm).");
      break;
    case Action::ResetHome:
      // What the board will believe: its estimate keeps going while the truth is moved home.
      if (armed && in_air)
        return confirm(Action::ResetHome,
                       "Reset IN THE AIR? The vehicle is put on the ground at home, motors stopped, but the board's estimate "
                       "keeps flying: PX4 sees a jump and may fail its estimator checks. Land and disarm first, or restart "
                       "the board afterwards.");
      if (armed)
        return confirm(Action::ResetHome,
                       "Reset to home while ARMED? The vehicle is put back on the ground at home, motors stopped, while PX4 "
                       "stays armed and sees its position jump there. Disarm first, or restart the board afterwards.");
      break;
    case Action::FlyTrajectory:
      if (model.trajectory_running) return confirm(Action::StopTrajectory, "A trajectory is being flown. Stop it?");
      break;
    default: break;
  }
  return start(action, "", actions);
}

Dispatcher::Result Dispatcher::on_key(const Key& key, const DashboardModel& model, DashboardActions* actions) {
  if (key.kind == Key::Kind::None || key.kind == Key::Kind::Resize) return {};
  // The messages scroll while typing a shell command too (to read its output).
  const auto mode = interaction_.mode;
  if (mode != Interaction::Mode::Confirm && mode != Interaction::Mode::Help && mode != Interaction::Mode::FaultMenu && scroll(key))
    return {};
  switch (interaction_.mode) {
    case Interaction::Mode::FaultMenu: {
      const auto r = interaction_.fault_menu.on_key(key, model.active_faults);
      if (!r.close) return {};
      enter(Interaction::Mode::Normal);
      if (r.command) return start(Action::Fault, *r.command, actions);
      return {};
    }
    case Interaction::Mode::Help:
      enter(Interaction::Mode::Normal);
      return {};
    case Interaction::Mode::Confirm: {
      const auto action = pending_;
      enter(Interaction::Mode::Normal);
      pending_.reset();
      if (key.kind == Key::Kind::Char && (key.ch == 'y' || key.ch == 'Y') && action) return start(*action, "", actions);
      return {false, std::string(action ? to_string(*action) : "action") + ": cancelled"};
    }
    case Interaction::Mode::Prompt:
      switch (key.kind) {
        case Key::Kind::Escape:
          enter(Interaction::Mode::Normal);
          return {};
        case Key::Kind::Enter: {
          std::string line = interaction_.input;
          enter(Interaction::Mode::Normal);
          const auto first = line.find_first_not_of(' ');
          if (first == std::string::npos) return {};
          return start(Action::Shell, line.substr(first), actions);
        }
        case Key::Kind::Backspace:
          if (!interaction_.input.empty()) interaction_.input.pop_back();
          return {};
        case Key::Kind::Char:
          if (interaction_.input.size() < kMaxCommandLength) interaction_.input += key.ch;
          return {};
        default: return {};
      }
    case Interaction::Mode::Normal: break;
  }
  if (key.kind != Key::Kind::Char) return {};
  switch (key.ch) {
    case 'q': return {true, std::nullopt};
    case '?':
    case 'h':
      enter(Interaction::Mode::Help);
      return {};
    case 'a': return request(Action::Arm, model, actions);
    case 'd': return request(Action::Disarm, model, actions);
    case 't': return request(Action::Takeoff, model, actions);
    case 'l': return request(Action::Land, model, actions);
    case 'p': return request(Action::TogglePause, model, actions);
    case 'r': return request(Action::ResetHome, model, actions);
    case 'f': return request(Action::FlyTrajectory, model, actions);
    case 's':
      if (actions == nullptr || actions->refusal(Action::Shell)) return start(Action::Shell, "", actions);
      enter(Interaction::Mode::Prompt, "", "shell (Enter runs, Esc cancels)> ");
      return {};
    case 'x':
      if (actions == nullptr || actions->refusal(Action::Fault)) return start(Action::Fault, "", actions);
      enter(Interaction::Mode::FaultMenu);
      return {};
    default: return {};
  }
}

}  // namespace hitl::tui
