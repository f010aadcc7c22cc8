// The dashboard's interaction drawn from fixed models onto the in-memory screen: the messages panel
// scrolled back, the last key's outcome in the header, the footer's keys per command, the
// confirmation, the prompt and the help overlay.
#include <gtest/gtest.h>

#include <string>

#include "tests/tui/render_screen.h"
#include "tests/tui/sample_model.h"
#include "tui/keys.h"
#include "tui/layout.h"
#include "tui/message_log.h"
#include "tui/panels.h"

namespace hitl::tui {
namespace {

using test::draw;

// Issue 18: the messages panel scrolls (PgUp/PgDn, Home, End) and says where it is; lines that
// arrive while scrolled back do not move the view.
TEST(Render, MessagesScrollBackAndStayWhileLinesArrive) {
  auto m = test::sample_model();
  m.messages.clear();
  for (int i = 0; i < 40; ++i) m.messages.push_back({1.0 * i, Severity::Info, "entry " + std::to_string(i)});
  const Rect inner = layout_for(80, 24, m).messages.inner();
  Dispatcher d;
  d.set_messages_view(message_row_count(m.messages, inner.w), inner.h);
  auto shown = [&](const DashboardModel& model) { return draw(80, 24, model, d.interaction()); };
  EXPECT_GE(shown(m).find("entry 39").second, 0);  // following the newest
  d.on_key({Key::Kind::PageUp, 0}, m, nullptr);
  auto s = shown(m);
  SCOPED_TRACE(s.dump());
  EXPECT_EQ(s.find("entry 39").second, -1);
  const int page = inner.h - 1;
  EXPECT_GE(s.find("entry " + std::to_string(40 - inner.h - page)).second, 0);
  EXPECT_GE(s.find(", End: newest").second, 0);
  // New lines do not move what is being read.
  auto more = m;
  more.messages.push_back({41.0, Severity::Info, "entry 40"});
  d.set_messages_view(message_row_count(more.messages, inner.w), inner.h);
  EXPECT_EQ(shown(more).row(inner.y), s.row(inner.y));
  d.on_key({Key::Kind::Home, 0}, more, nullptr);
  EXPECT_GE(shown(more).find("entry 0 ").second, 0);
  // End follows the newest again; so does PgDn at the bottom.
  d.on_key({Key::Kind::End, 0}, more, nullptr);
  EXPECT_FALSE(d.interaction().messages_top);
  EXPECT_GE(shown(more).find("entry 40").second, 0);
  d.on_key({Key::Kind::PageUp, 0}, more, nullptr);
  for (int i = 0; i < 20; ++i) d.on_key({Key::Kind::PageDown, 0}, more, nullptr);
  EXPECT_FALSE(d.interaction().messages_top);
  // The scroll survives a question and the help overlay.
  d.on_key({Key::Kind::Home, 0}, more, nullptr);
  d.on_key(Key::character('?'), more, nullptr);
  d.on_key(Key::character('x'), more, nullptr);
  EXPECT_EQ(d.interaction().messages_top, 0);
}

// Issue 18: the last key's outcome stays in the header while the messages move on.
TEST(Render, TheLastKeysOutcomeIsPinnedInTheHeader) {
  MessageLog log;
  log.add_outcome(Severity::Error, "arm denied: Preflight Fail: ekf2 not aligned");
  for (int i = 0; i < 30; ++i) log.add(Severity::Info, "later line " + std::to_string(i));
  auto m = test::sample_model();
  m.messages = log.lines();
  m.outcome = log.outcome();
  ASSERT_TRUE(m.outcome);
  const auto s = draw(120, 40, m);
  SCOPED_TRACE(s.dump());
  const auto at = s.find("arm denied: Preflight Fail");
  EXPECT_EQ(at.second, 0);
  EXPECT_EQ(s.style_at(at.first, 0).color, Color::Bad);
  // At 80 columns it is cut to the room there is, never over the clock.
  const auto narrow = draw(80, 24, m);
  EXPECT_NE(narrow.row(0).find("sim 12.3 s  rtf 1.00  | "), std::string::npos) << narrow.row(0);
  EXPECT_NE(narrow.row(0).find("arm denied"), std::string::npos) << narrow.row(0);
}

// Issue 18: the footer and the help list only the keys that work on that dashboard.
TEST(Render, TheFooterListsOnlyTheKeysThatWorkHere) {
  auto sim = test::sample_model();
  const auto s = draw(120, 40, sim);
  EXPECT_EQ(s.row(39).rfind("a:arm d:disarm t:takeoff l:land p:pause r:reset f:fly s:shell PgUp/PgDn:messages ?:help q:quit", 0), 0u)
      << s.row(39);
  EXPECT_NE(draw(80, 24, sim).row(23).find("s:shell ?:help q:quit"), std::string::npos);  // the scroll keys are in the help

  auto bridge = sim;
  bridge.keys = "adtls";
  const auto b = draw(120, 40, bridge);
  EXPECT_EQ(b.row(39).rfind("a:arm d:disarm t:takeoff l:land s:shell PgUp/PgDn:messages ?:help q:quit", 0), 0u) << b.row(39);
  const auto bh = draw(120, 40, bridge, Interaction{Interaction::Mode::Help, "", "", ""});
  EXPECT_GE(bh.find("s  one shell command").second, 0) << bh.dump();
  EXPECT_EQ(bh.find("pause / resume").second, -1);

  auto inspect = sim;
  inspect.keys.clear();
  const auto i = draw(80, 24, inspect);
  EXPECT_EQ(i.row(23).rfind("PgUp/PgDn:messages ?:help q:quit", 0), 0u) << i.row(23);
  const auto ih = draw(80, 24, inspect, Interaction{Interaction::Mode::Help, "", "", ""});
  EXPECT_EQ(ih.find("arm").second, -1) << ih.dump();
  EXPECT_GE(ih.find("PgUp PgDn").second, 0);
}

TEST(Render, ConfirmationAndPromptInTheFooter) {
  Interaction confirm{Interaction::Mode::Confirm, "Disarm IN THE AIR? The motors stop and the vehicle falls (forced disarm).", "", ""};
  const auto s = draw(80, 24, test::sample_model(), confirm);
  EXPECT_NE(s.row(23).find("Disarm IN THE AIR?"), std::string::npos) << s.row(23);
  EXPECT_EQ(s.style_at(0, 23).color, Color::Warning);
  EXPECT_TRUE(s.style_at(0, 23).reverse);
  const auto wide = draw(200, 60, test::sample_model(), confirm);
  EXPECT_NE(wide.row(59).find("[y/N]"), std::string::npos);

  Interaction prompt{Interaction::Mode::Prompt, "", "shell> ", "qshell dsp_hitl status"};
  const auto p = draw(80, 24, test::sample_model(), prompt);
  EXPECT_EQ(p.row(23).rfind("shell> qshell dsp_hitl status_", 0), 0u) << p.row(23);
}

TEST(Render, HelpOverlay) {
  const auto s = draw(80, 24, test::sample_model(), Interaction{Interaction::Mode::Help, "", "", ""});
  EXPECT_GE(s.find("Keys and colours").second, 0) << s.dump();
  EXPECT_GE(s.find("d  disarm (asks first in the air)").second, 0);
  EXPECT_GE(s.find("green within 5 %").second, 0);
}

}  // namespace
}  // namespace hitl::tui
