// The key dispatcher: actions, the confirmations dangerous keys ask for, the shell prompt, help,
// refusals, quitting.
#include <gtest/gtest.h>

#include <vector>

#include "tests/tui/sample_model.h"
#include "tui/keys.h"
#include "tui/memory_screen.h"

namespace hitl::tui {
namespace {

class FakeActions : public DashboardActions {
 public:
  std::optional<std::string> refusal(Action a) const override {
    if (refuse && *refuse == a) return "no autopilot yet";
    return std::nullopt;
  }
  void perform(Action a, const std::string& argument) override { done.emplace_back(a, argument); }
  std::optional<Action> refuse;
  std::vector<std::pair<Action, std::string>> done;
};

DashboardModel on_ground() {
  auto m = test::sample_model();
  m.vehicle->in_air = false;
  m.vehicle->armed = false;
  return m;
}

TEST(Keys, PlainActionsRunAtOnce) {
  Dispatcher d;
  FakeActions a;
  const auto m = on_ground();
  for (char c : {'a', 't', 'l', 'p', 'r', 'd', 'f'}) EXPECT_FALSE(d.on_key(Key::character(c), m, &a).quit);
  ASSERT_EQ(a.done.size(), 7u);
  EXPECT_EQ(a.done[0].first, Action::Arm);
  EXPECT_EQ(a.done[1].first, Action::Takeoff);
  EXPECT_EQ(a.done[2].first, Action::Land);
  EXPECT_EQ(a.done[3].first, Action::TogglePause);
  EXPECT_EQ(a.done[4].first, Action::ResetHome);  // disarmed: no question
  EXPECT_EQ(a.done[5].first, Action::Disarm);     // on the ground: no question
  EXPECT_EQ(a.done[6].first, Action::FlyTrajectory);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Normal);
}

TEST(Keys, DisarmInTheAirAsksThenForces) {
  Dispatcher d;
  FakeActions a;
  const auto m = test::sample_model();  // armed, in air
  d.on_key(Key::character('d'), m, &a);
  EXPECT_TRUE(a.done.empty());
  ASSERT_EQ(d.interaction().mode, Interaction::Mode::Confirm);
  EXPECT_NE(d.interaction().question.find("IN THE AIR"), std::string::npos);
  // Anything but y cancels, and says so.
  auto r = d.on_key(Key::character('n'), m, &a);
  EXPECT_TRUE(a.done.empty());
  ASSERT_TRUE(r.note);
  EXPECT_NE(r.note->find("cancelled"), std::string::npos);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Normal);
  // y forces the disarm.
  d.on_key(Key::character('d'), m, &a);
  d.on_key(Key::character('y'), m, &a);
  ASSERT_EQ(a.done.size(), 1u);
  EXPECT_EQ(a.done[0].first, Action::ForceDisarm);
  // Escape cancels too; q during a question does not quit.
  d.on_key(Key::character('d'), m, &a);
  EXPECT_FALSE(d.on_key(Key::character('q'), m, &a).quit);
  EXPECT_EQ(a.done.size(), 1u);
}

TEST(Keys, ResetWhileArmedAndStoppingATrajectoryAsk) {
  Dispatcher d;
  FakeActions a;
  auto m = test::sample_model();
  d.on_key(Key::character('r'), m, &a);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Confirm);
  d.on_key(Key::character('y'), m, &a);
  ASSERT_EQ(a.done.size(), 1u);
  EXPECT_EQ(a.done[0].first, Action::ResetHome);
  m.trajectory_running = true;
  d.on_key(Key::character('f'), m, &a);
  EXPECT_NE(d.interaction().question.find("Stop it?"), std::string::npos);
  d.on_key(Key::character('Y'), m, &a);
  ASSERT_EQ(a.done.size(), 2u);
  EXPECT_EQ(a.done[1].first, Action::StopTrajectory);
}

// Issue 18: a reset while armed says what the board will believe, and what to do instead; the
// question is shown whole even at 80 columns.
TEST(Keys, ResetWhileArmedSaysWhatTheBoardWillBelieve) {
  Dispatcher d;
  FakeActions a;
  auto m = test::sample_model();  // armed, in the air
  d.on_key(Key::character('r'), m, &a);
  const std::string q = d.interaction().question;
  EXPECT_NE(q.find("IN THE AIR"), std::string::npos) << q;
  EXPECT_NE(q.find("estimate keeps flying"), std::string::npos) << q;
  EXPECT_NE(q.find("PX4 sees a jump"), std::string::npos) << q;
  EXPECT_NE(q.find("Land and disarm first, or restart the board"), std::string::npos) << q;
  MemoryScreen s(80, 24);
  render(s, m, d.interaction());
  SCOPED_TRACE(s.dump());
  EXPECT_GE(s.find("Confirm").second, 0);
  EXPECT_GE(s.find("board afterwards.").second, 0);  // the question's end, wrapped
  EXPECT_NE(s.row(23).find("[y/N]"), std::string::npos);
  d.on_key(Key::character('n'), m, &a);
  EXPECT_TRUE(a.done.empty());

  m.vehicle->in_air = false;  // armed on the ground
  d.on_key(Key::character('r'), m, &a);
  EXPECT_NE(d.interaction().question.find("while ARMED"), std::string::npos);
  EXPECT_NE(d.interaction().question.find("Disarm first"), std::string::npos);
}

TEST(Keys, ShellPrompt) {
  Dispatcher d;
  FakeActions a;
  const auto m = on_ground();
  d.on_key(Key::character('s'), m, &a);
  ASSERT_EQ(d.interaction().mode, Interaction::Mode::Prompt);
  for (char c : std::string("ver alx")) d.on_key(Key::character(c), m, &a);
  d.on_key({Key::Kind::Backspace, 0}, m, &a);
  d.on_key(Key::character('l'), m, &a);
  EXPECT_EQ(d.interaction().input, "ver all");
  // Keys type into the prompt: q does not quit, a does not arm.
  EXPECT_FALSE(d.on_key(Key::character('q'), m, &a).quit);
  d.on_key({Key::Kind::Backspace, 0}, m, &a);
  d.on_key({Key::Kind::Enter, 0}, m, &a);
  ASSERT_EQ(a.done.size(), 1u);
  EXPECT_EQ(a.done[0].first, Action::Shell);
  EXPECT_EQ(a.done[0].second, "ver all");
  // Escape leaves without running; an empty line runs nothing.
  d.on_key(Key::character('s'), m, &a);
  d.on_key(Key::character('x'), m, &a);
  d.on_key({Key::Kind::Escape, 0}, m, &a);
  d.on_key(Key::character('s'), m, &a);
  d.on_key({Key::Kind::Enter, 0}, m, &a);
  EXPECT_EQ(a.done.size(), 1u);
  // The line has a limit.
  d.on_key(Key::character('s'), m, &a);
  for (int i = 0; i < 500; ++i) d.on_key(Key::character('x'), m, &a);
  EXPECT_EQ(d.interaction().input.size(), Dispatcher::kMaxCommandLength);
}

// x opens the fault menu (fault_menu_test.cpp has its keys); what it starts goes through the same
// Action::Fault the typed prompt gave, and the shell's prompt is still the shell's.
TEST(Keys, XOpensTheFaultMenuWhoseCommandsAreFaultActions) {
  Dispatcher d;
  FakeActions a;
  const auto m = on_ground();
  d.on_key(Key::character('x'), m, &a);
  ASSERT_EQ(d.interaction().mode, Interaction::Mode::FaultMenu);
  // The typed form inside the menu: `:` then the line.
  d.on_key(Key::character(':'), m, &a);
  for (char c : std::string("gps-loss+10")) d.on_key(Key::character(c), m, &a);
  d.on_key({Key::Kind::Enter, 0}, m, &a);
  ASSERT_EQ(a.done.size(), 1u);
  EXPECT_EQ(a.done[0].first, Action::Fault);
  EXPECT_EQ(a.done[0].second, "gps-loss+10");
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Normal);
  // Keys in the menu are the menu's: q filters, PgUp moves the list, not the messages.
  d.on_key(Key::character('x'), m, &a);
  EXPECT_FALSE(d.on_key(Key::character('q'), m, &a).quit);
  d.on_key({Key::Kind::PageUp, 0}, m, &a);
  EXPECT_FALSE(d.interaction().messages_top);
  d.on_key({Key::Kind::Escape, 0}, m, &a);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Normal);
  d.on_key(Key::character('s'), m, &a);
  d.on_key(Key::character('v'), m, &a);
  d.on_key({Key::Kind::Enter, 0}, m, &a);
  ASSERT_EQ(a.done.size(), 2u);
  EXPECT_EQ(a.done[1].first, Action::Shell);
  // Refused where there is no simulator: said, no menu.
  a.refuse = Action::Fault;
  const auto r = d.on_key(Key::character('x'), m, &a);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Normal);
  ASSERT_TRUE(r.note);
  EXPECT_EQ(*r.note, "fault: no autopilot yet");
}

TEST(Keys, RefusalsAndViewOnlyDashboards) {
  Dispatcher d;
  FakeActions a;
  a.refuse = Action::Arm;
  auto r = d.on_key(Key::character('a'), on_ground(), &a);
  EXPECT_TRUE(a.done.empty());
  ASSERT_TRUE(r.note);
  EXPECT_EQ(*r.note, "arm: no autopilot yet");
  // No actions at all (inspect): every action key says so; ? and q still work.
  r = d.on_key(Key::character('t'), on_ground(), nullptr);
  ASSERT_TRUE(r.note);
  EXPECT_NE(r.note->find("only shows"), std::string::npos);
  d.on_key(Key::character('?'), on_ground(), nullptr);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Help);
  d.on_key(Key::character('x'), on_ground(), nullptr);  // any key closes the help
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Normal);
  EXPECT_TRUE(d.on_key(Key::character('q'), on_ground(), nullptr).quit);
}

TEST(Keys, ResizeAndNothingChangeNothing) {
  Dispatcher d;
  FakeActions a;
  d.on_key(Key::character('s'), on_ground(), &a);
  d.on_key({Key::Kind::Resize, 0}, on_ground(), &a);
  EXPECT_EQ(d.interaction().mode, Interaction::Mode::Prompt);
  EXPECT_TRUE(a.done.empty());
}

}  // namespace
}  // namespace hitl::tui
