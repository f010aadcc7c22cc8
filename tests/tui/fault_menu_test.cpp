// The fault menu (`x` on the sim dashboard): key sequences to the commands it gives and the state
// it is in; drawn onto the in-memory screen at 80x24 and larger.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "tests/tui/render_screen.h"
#include "tests/tui/sample_model.h"
#include "tui/collect.h"
#include "tui/fault_menu.h"
#include "tui/keys.h"

namespace hitl::tui {
namespace {

using Kind = FaultMenu::Row::Kind;

Key key(Key::Kind k) { return {k, 0}; }

FaultMenu::Result type(FaultMenu& menu, const std::string& text, const std::vector<ActiveFault>& active = {}) {
  FaultMenu::Result r;
  for (char c : text) r = menu.on_key(Key::character(c), active);
  return r;
}

std::vector<ActiveFault> two_active() {
  return {{"gps-loss", "gps-loss", 10.0, 5.0}, {"motor", "motor:2,0.6", 3.0, std::nullopt}};
}

/// The selected row's fault name ("" when it is not a catalogue fault).
std::string selected_fault(const FaultMenu& menu, const std::vector<ActiveFault>& active = {}) {
  const auto rows = menu.rows(active);
  const int i = menu.selected(active);
  return i >= 0 && rows[static_cast<std::size_t>(i)].kind == Kind::Fault ? rows[static_cast<std::size_t>(i)].fault->name : "";
}

TEST(FaultMenu, ListsTheActiveFaultsFirstThenEveryFaultByGroup) {
  FaultMenu menu;
  const auto active = two_active();
  const auto rows = menu.rows(active);
  ASSERT_GE(rows.size(), 5u);
  EXPECT_EQ(rows[0].kind, Kind::Heading);
  EXPECT_EQ(rows[0].heading, "Active faults (2)");
  EXPECT_EQ(rows[1].kind, Kind::Active);
  EXPECT_EQ(rows[1].active->text, "gps-loss");
  EXPECT_EQ(rows[2].active->text, "motor:2,0.6");
  EXPECT_EQ(rows[3].kind, Kind::ClearAll);
  // Then the groups in order, each fault once, in its group.
  std::vector<std::string> headings;
  std::set<std::string> names;
  faults::FaultGroup group = faults::FaultGroup::Vehicle;
  for (std::size_t i = 4; i < rows.size(); ++i) {
    if (rows[i].kind == Kind::Heading) {
      headings.push_back(rows[i].heading);
      group = faults::kFaultGroups[headings.size() - 1];
      continue;
    }
    ASSERT_EQ(rows[i].kind, Kind::Fault);
    EXPECT_EQ(rows[i].fault->group, group) << rows[i].fault->name;
    EXPECT_TRUE(names.insert(rows[i].fault->name).second);
  }
  EXPECT_EQ(headings, (std::vector<std::string>{"Vehicle", "IMU", "Mag", "Baro", "GPS", "Optional sensors", "VIO", "Environment",
                                                "HIL link", "VIO link", "Board"}));
  EXPECT_EQ(names.size(), faults::fault_catalogue().size());
  // The selection starts on the first active fault; without any, on the first fault.
  EXPECT_EQ(menu.selected(active), 1);
  EXPECT_EQ(selected_fault(menu), "motor");
}

TEST(FaultMenu, EnterOrCClearsAnActiveFaultAndClearAllEndsEvery) {
  const auto active = two_active();
  FaultMenu menu;
  auto r = menu.on_key(key(Key::Kind::Enter), active);
  EXPECT_TRUE(r.close);
  EXPECT_EQ(r.command, "clear gps-loss");
  FaultMenu by_c;
  by_c.on_key(key(Key::Kind::Down), active);
  r = by_c.on_key(Key::character('c'), active);
  EXPECT_EQ(r.command, "clear motor");
  FaultMenu all;
  all.on_key(key(Key::Kind::Down), active);
  all.on_key(key(Key::Kind::Down), active);
  r = all.on_key(key(Key::Kind::Enter), active);
  EXPECT_EQ(r.command, "clear");
  // On a catalogue fault c is a letter of the filter, not a clear.
  FaultMenu on_fault;
  r = on_fault.on_key(Key::character('c'), {});
  EXPECT_FALSE(r.close);
  EXPECT_EQ(on_fault.filter(), "c");
}

TEST(FaultMenu, LettersFilterByNameOrGroupAndBackspaceEdits) {
  FaultMenu menu;
  type(menu, "gps-l");
  EXPECT_EQ(menu.filter(), "gps-l");
  EXPECT_EQ(selected_fault(menu), "gps-loss");
  int faults = 0;
  for (const auto& row : menu.rows({})) faults += row.kind == Kind::Fault;
  EXPECT_EQ(faults, 1);
  // A group's name matches its faults: "imu" includes gyro-bias.
  FaultMenu imu;
  type(imu, "IMU");
  bool gyro = false;
  for (const auto& row : imu.rows({})) gyro = gyro || (row.kind == Kind::Fault && std::string(row.fault->name) == "gyro-bias");
  EXPECT_TRUE(gyro);
  // Nothing matches: one row says so; Backspace brings the matches back.
  FaultMenu none;
  type(none, "zz");
  const auto rows = none.rows({});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].kind, Kind::Nothing);
  EXPECT_EQ(none.selected({}), -1);
  EXPECT_FALSE(none.on_key(key(Key::Kind::Enter), {}).close);
  none.on_key(key(Key::Kind::Backspace), {});
  none.on_key(key(Key::Kind::Backspace), {});
  EXPECT_EQ(none.filter(), "");
  EXPECT_EQ(selected_fault(none), "motor");
  // The filter has a limit.
  FaultMenu longer;
  type(longer, std::string(100, 'a'));
  EXPECT_EQ(longer.filter().size(), FaultMenu::kMaxFilterLength);
}

TEST(FaultMenu, EnterOnAFaultOpensItsLinePrefilledThenStartsIt) {
  FaultMenu menu;
  type(menu, "gps-loss");
  EXPECT_FALSE(menu.on_key(key(Key::Kind::Enter), {}).close);
  ASSERT_EQ(menu.page(), FaultMenu::Page::Line);
  ASSERT_NE(menu.fault(), nullptr);
  EXPECT_EQ(menu.line(), "gps-loss");
  type(menu, "+10");
  const auto r = menu.on_key(key(Key::Kind::Enter), {});
  EXPECT_TRUE(r.close);
  EXPECT_EQ(r.command, "gps-loss+10");

  // Arguments come pre-filled with the catalogue's example.
  FaultMenu motor;
  type(motor, "motor");
  motor.on_key(key(Key::Kind::Enter), {});
  EXPECT_EQ(motor.line(), "motor:2,0.75");
  EXPECT_EQ(motor.on_key(key(Key::Kind::Enter), {}).command, "motor:2,0.75");
}

TEST(FaultMenu, BadArgumentsAreRefusedWithTheCataloguesMessageAndTheMenuStays) {
  FaultMenu menu;
  type(menu, "motor");
  menu.on_key(key(Key::Kind::Enter), {});
  for (int i = 0; i < 4; ++i) menu.on_key(key(Key::Kind::Backspace), {});  // "motor:2,"
  type(menu, "9");
  auto r = menu.on_key(key(Key::Kind::Enter), {});
  EXPECT_FALSE(r.close);
  EXPECT_FALSE(r.command);
  EXPECT_EQ(menu.page(), FaultMenu::Page::Line);
  EXPECT_EQ(menu.error(), faults::parse_live_fault("motor:2,9").error().message);
  EXPECT_NE(menu.error().find("k must be within 0..2"), std::string::npos) << menu.error();
  // Editing clears the message; Esc goes back to the list, a second Esc closes.
  menu.on_key(key(Key::Kind::Backspace), {});
  EXPECT_EQ(menu.error(), "");
  menu.on_key(key(Key::Kind::Escape), {});
  EXPECT_EQ(menu.page(), FaultMenu::Page::List);
  EXPECT_EQ(selected_fault(menu), "motor");  // where it was
  r = menu.on_key(key(Key::Kind::Escape), {});
  EXPECT_TRUE(r.close);
  EXPECT_FALSE(r.command);
  // gust needs its duration: said by the catalogue too.
  FaultMenu gust;
  type(gust, "gust");
  gust.on_key(key(Key::Kind::Enter), {});
  EXPECT_EQ(gust.line(), "gust:5,0+6");
  for (int i = 0; i < 2; ++i) gust.on_key(key(Key::Kind::Backspace), {});
  EXPECT_FALSE(gust.on_key(key(Key::Kind::Enter), {}).close);
  EXPECT_NE(gust.error().find("needs a duration"), std::string::npos) << gust.error();
}

TEST(FaultMenu, ColonOpensTheTypedFormWhichTakesEverythingThePromptDid) {
  for (const std::string typed : {"hil-delay:20+5", "clear motor", "clear", "  imu-bias:1e+0,0,0  "}) {
    FaultMenu menu;
    menu.on_key(Key::character(':'), {});
    ASSERT_EQ(menu.page(), FaultMenu::Page::Line);
    EXPECT_EQ(menu.fault(), nullptr);
    EXPECT_EQ(menu.line(), "");
    type(menu, typed);
    const auto r = menu.on_key(key(Key::Kind::Enter), {});
    EXPECT_TRUE(r.close) << typed;
    EXPECT_EQ(r.command.value_or(""), typed.find_first_not_of(' ') == 0 ? typed : "imu-bias:1e+0,0,0");
  }
  FaultMenu empty;
  empty.on_key(Key::character(':'), {});
  EXPECT_FALSE(empty.on_key(key(Key::Kind::Enter), {}).close);
  EXPECT_NE(empty.error().find("type a fault"), std::string::npos);
  FaultMenu unknown;
  unknown.on_key(Key::character(':'), {});
  type(unknown, "gps-lost");
  EXPECT_FALSE(unknown.on_key(key(Key::Kind::Enter), {}).close);
  EXPECT_NE(unknown.error().find("unknown fault 'gps-lost'"), std::string::npos) << unknown.error();
  type(unknown, std::string(500, '1'));
  EXPECT_EQ(unknown.line().size(), FaultMenu::kMaxLineLength);
}

TEST(FaultMenu, UpDownPagesHomeEndSkipHeadingsAndScroll) {
  FaultMenu menu;
  menu.set_page_rows(5);
  const auto rows = menu.rows({});
  EXPECT_EQ(menu.selected({}), 1);  // motor, under "Vehicle"
  menu.on_key(key(Key::Kind::Down), {});
  menu.on_key(key(Key::Kind::Down), {});
  EXPECT_EQ(selected_fault(menu), "payload");
  menu.on_key(key(Key::Kind::Down), {});  // over the "IMU" heading
  EXPECT_EQ(rows[static_cast<std::size_t>(menu.selected({}))].fault->group, faults::FaultGroup::Imu);
  EXPECT_EQ(menu.selected({}), 5);
  EXPECT_EQ(menu.top({}, 5), 1);  // scrolled by one to keep it in view
  menu.on_key(key(Key::Kind::Up), {});
  menu.on_key(key(Key::Kind::Up), {});
  menu.on_key(key(Key::Kind::Up), {});
  EXPECT_EQ(selected_fault(menu), "motor");
  EXPECT_EQ(menu.top({}, 5), 0);  // its heading back in view
  menu.on_key(key(Key::Kind::Up), {});  // at the top: stays
  EXPECT_EQ(selected_fault(menu), "motor");
  menu.on_key(key(Key::Kind::PageDown), {});
  EXPECT_EQ(menu.selected({}), 5);  // four rows down (a page, one kept)
  menu.on_key(key(Key::Kind::End), {});
  EXPECT_EQ(selected_fault(menu), "actuators-stale");
  EXPECT_EQ(menu.top({}, 5), static_cast<int>(rows.size()) - 5);
  menu.on_key(key(Key::Kind::Down), {});
  EXPECT_EQ(selected_fault(menu), "actuators-stale");
  menu.on_key(key(Key::Kind::PageUp), {});
  EXPECT_LT(menu.selected({}), static_cast<int>(rows.size()) - 1);
  menu.on_key(key(Key::Kind::Home), {});
  EXPECT_EQ(selected_fault(menu), "motor");
  EXPECT_EQ(menu.top({}, 5), 0);
  // A smaller screen than the keys saw: the drawing keeps the selection in view.
  menu.on_key(key(Key::Kind::End), {});
  EXPECT_EQ(menu.top({}, 2), static_cast<int>(rows.size()) - 2);
}

TEST(FaultMenu, AnActiveFaultThatEndsWhileSelectedMovesTheSelectionOn) {
  auto active = two_active();
  FaultMenu menu;
  menu.on_key(key(Key::Kind::Down), active);  // motor:2,0.6
  active.pop_back();                          // it ended
  const auto rows = menu.rows(active);
  const int i = menu.selected(active);
  ASSERT_GE(i, 0);
  EXPECT_TRUE(rows[static_cast<std::size_t>(i)].selectable());
  EXPECT_EQ(rows[static_cast<std::size_t>(i)].kind, Kind::ClearAll);  // the row now where it was
  // Everything ended: the selection lands on a catalogue fault and Enter does not clear.
  active.clear();
  EXPECT_EQ(menu.on_key(key(Key::Kind::Enter), active).command, std::nullopt);
}

// What the menu and the state line list: the session's records not ended, with what is left of
// each duration; the state line names three and counts the rest.
TEST(FaultMenu, ActiveFaultsComeFromTheSessionsRecords) {
  const std::vector<faults::FaultRecord> records = {{"gps-loss", {}, 2.0, std::nullopt, 10.0},
                                                     {"motor", {2, 0.6}, 3.0, std::nullopt, std::nullopt},
                                                     {"hil-delay", {20}, 1.0, 4.0, std::nullopt},  // ended
                                                     {"gps-jump", {20, 0}, 4.0, std::nullopt, 1.0}};
  const auto active = active_faults_from(records, 6.5);
  ASSERT_EQ(active.size(), 3u);
  EXPECT_EQ(active[0].text, "gps-loss");
  EXPECT_DOUBLE_EQ(active[0].left_s.value_or(-1), 5.5);
  EXPECT_EQ(active[1].text, "motor:2,0.6");
  EXPECT_EQ(active[1].name, "motor");
  EXPECT_FALSE(active[1].left_s);
  EXPECT_DOUBLE_EQ(active[2].left_s.value_or(-1), 0.0);  // due to end at the next step: never negative
  EXPECT_EQ(active_faults_text(active), "faults: gps-loss (6 s left) motor:2,0.6 gps-jump:20,0 (0 s left)");
  EXPECT_EQ(active_faults_text({}), "");
  std::vector<ActiveFault> many(8, ActiveFault{"vio-dup", "vio-dup:0.1", 0, std::nullopt});
  EXPECT_EQ(active_faults_text(many), "faults: vio-dup:0.1 vio-dup:0.1 vio-dup:0.1 +5 more (x lists them)");
}

// Drawing: the menu over the dashboard at 80x24 (a scrolling list) and on a large terminal.
Interaction menu_open(FaultMenu menu = {}) {
  Interaction in;
  in.mode = Interaction::Mode::FaultMenu;
  in.fault_menu = std::move(menu);
  return in;
}

DashboardModel with_faults() {
  auto m = test::sample_model();
  m.keys = "adtlprfsx";
  m.active_faults = two_active();
  return m;
}

TEST(FaultMenuRender, At80x24TheListScrollsUnderItsFilterLine) {
  FaultMenu menu;
  menu.set_page_rows(fault_menu_page_rows(80, 24));
  const auto s = test::draw(80, 24, with_faults(), menu_open(menu));
  SCOPED_TRACE(s.dump());
  EXPECT_GE(s.find("Faults: start or clear").second, 1);
  EXPECT_GE(s.find("type to filter by name or group").second, 0);
  EXPECT_GE(s.find("Active faults (2)").second, 0);
  const auto [x, y] = s.find("gps-loss        since 10.0 s, 5.0 s left");
  ASSERT_GE(y, 0);
  EXPECT_TRUE(s.style_at(x, y).reverse);  // selected
  EXPECT_EQ(s.style_at(x, y).color, Color::Warning);
  EXPECT_GE(s.find("motor:2,0.6     since 3.0 s, until cleared").second, 0);
  EXPECT_GE(s.find("clear all").second, 0);
  EXPECT_GE(s.find("Vehicle").second, 0);
  EXPECT_GE(s.find("prop-damage").second, 0);
  EXPECT_EQ(s.find("actuators-stale").second, -1);  // further down
  EXPECT_GE(s.find("Enter or c ends every active gps-loss now").second, 0);
  EXPECT_GE(s.find("1/47").second, 0);  // 2 active, clear all, 44 faults
  EXPECT_NE(s.row(23).find("Enter:pick"), std::string::npos) << s.row(23);
  EXPECT_NE(s.row(23).find("Esc:close"), std::string::npos) << s.row(23);
  // The header stays above it; every row within the screen's 80 columns.
  EXPECT_NE(s.row(0).find("hitl sim"), std::string::npos);

  // End: the last group in view, the first ones scrolled away.
  menu.on_key(key(Key::Kind::End), two_active());
  const auto end = test::draw(80, 24, with_faults(), menu_open(menu));
  EXPECT_GE(end.find("Board").second, 0) << end.dump();
  EXPECT_GE(end.find("actuators-stale").second, 0) << end.dump();
  EXPECT_EQ(end.find("Active faults").second, -1) << end.dump();
  EXPECT_GE(end.find("47/47").second, 0) << end.dump();
}

TEST(FaultMenuRender, TheLineShowsTheArgumentsAndTheRefusal) {
  FaultMenu menu;
  type(menu, "motor");
  menu.on_key(key(Key::Kind::Enter), {});
  auto s = test::draw(80, 24, with_faults(), menu_open(menu));
  SCOPED_TRACE(s.dump());
  EXPECT_GE(s.find("Start motor (vehicle)").second, 0);
  EXPECT_GE(s.find("motor i's (PX4 order) thrust").second, 0);
  EXPECT_GE(s.find("i           0 .. 3, whole").second, 0);
  EXPECT_GE(s.find("k           0 .. 2").second, 0);
  EXPECT_GE(s.find("> motor:2,0.75_").second, 0);
  EXPECT_NE(s.row(23).find("Enter:start now"), std::string::npos) << s.row(23);
  for (int i = 0; i < 4; ++i) menu.on_key(key(Key::Kind::Backspace), {});
  type(menu, "9");
  EXPECT_FALSE(menu.on_key(key(Key::Kind::Enter), {}).close);
  s = test::draw(80, 24, with_faults(), menu_open(menu));
  const auto [x, y] = s.find("k must be within 0..2");
  ASSERT_GE(y, 0) << s.dump();
  EXPECT_EQ(s.style_at(x, y).color, Color::Bad);
  // Optional arguments say so.
  FaultMenu degrade;
  type(degrade, "gps-degrade");
  degrade.on_key(key(Key::Kind::Enter), {});
  const auto d = test::draw(80, 24, with_faults(), menu_open(degrade));
  EXPECT_GE(d.find("epv_m       0 .. 655, optional").second, 0) << d.dump();
  EXPECT_GE(d.find("fix         0 .. 6, whole").second, 0) << d.dump();
}

TEST(FaultMenuRender, OnALargeTerminalEveryGroupFitsInOneBox) {
  FaultMenu menu;
  menu.set_page_rows(fault_menu_page_rows(200, 80));
  const auto s = test::draw(200, 80, with_faults(), menu_open(menu));
  SCOPED_TRACE(s.dump());
  for (const char* text : {"Active faults (2)", "Vehicle", "HIL link", "VIO link", "Board", "actuators-stale",
                           "no HIL_GPS is sent (the receiver lost every satellite)"})
    EXPECT_GE(s.find(text).second, 0) << text;
  const Rect box = fault_menu_box(200, 80);
  EXPECT_EQ(box.w, 100);
  EXPECT_EQ(s.find("Faults: start or clear").first, box.x + 2);
}

}  // namespace
}  // namespace hitl::tui
