// --fault specs, scenario files and the schedule: good and bad input, starts and ends in time.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/faults/fault_schedule.h"
#include "engine/faults/scenario.h"

namespace hitl::faults {
namespace {

TEST(FaultSpec, ParsesNameArgsStartAndDuration) {
  auto f = parse_fault("gps-loss@20+10");
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_EQ(f->kind, FaultKind::GpsLoss);
  EXPECT_DOUBLE_EQ(f->start_s, 20);
  ASSERT_TRUE(f->duration_s);
  EXPECT_DOUBLE_EQ(*f->duration_s, 10);
  auto m = parse_fault("motor:2,0.6@15");
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(m->args, (std::vector<double>{2, 0.6}));
  EXPECT_FALSE(m->duration_s);
  EXPECT_EQ(m->text(), "motor:2,0.6@15");
  auto d = parse_fault("hil-delay:20");
  ASSERT_TRUE(d);
  EXPECT_DOUBLE_EQ(d->start_s, 0);
  EXPECT_TRUE(parse_fault("gps-degrade:2,4,5"));      // epv optional
  EXPECT_TRUE(parse_fault("gps-degrade:2,4,5,8@1e+1"));  // an exponent is not a duration
}

TEST(FaultSpec, RefusesBadInputNamingTheFaultAndTheProblem) {
  auto suggest = [](const std::string& n) { return n == "gps-los" ? std::string("gps-loss") : std::string(); };
  const std::pair<const char*, const char*> bad[] = {
      {"gps-los@20", "did you mean 'gps-loss'"},
      {"motor:2@15", "fault motor: takes 2 arguments (motor:i,k), got 1"},
      {"gps-loss:1", "fault gps-loss: takes 0 arguments"},
      {"imu-bias:nan,0,0", "ax_m_s2: 'nan' is not a finite number"},
      {"imu-bias:0,0", "takes 3 arguments"},
      {"gps-loss@20+-3", "the duration must be more than 0"},
      {"gps-loss@-1", "the start time must be 0.."},
      {"gps-loss@x", "the start time after '@': 'x' is not a number"},
      {"motor:4,0.5", "i must be within 0..3"},
      {"motor:1.5,0.5", "i must be a whole number"},
      {"hil-drop:1.5", "p must be within 0..1"},
      {"gps-degrade:2,4", "takes 3 to 4 arguments"},
  };
  for (const auto& [text, what] : bad) {
    auto f = parse_fault(text, suggest);
    ASSERT_FALSE(f) << text;
    EXPECT_NE(f.error().message.find(what), std::string::npos) << text << ": " << f.error().message;
    EXPECT_EQ(f.error().kind, ErrorKind::Input) << text;  // the user's value: exit 2, whichever option gave it
  }
}

TEST(Scenario, ReadsEventsWithArrayOrStringArgs) {
  auto s = parse_scenario(R"({"description": "x", "events": [
      {"at_s": 20, "fault": "gps-loss", "duration_s": 10},
      {"at_s": 15, "fault": "motor", "args": [2, 0.6]},
      {"at_s": 1, "fault": "imu-bias", "args": "0.5,0,0"}]})", "scenario");
  ASSERT_TRUE(s) << s.error().message;
  ASSERT_EQ(s->size(), 3u);
  EXPECT_EQ((*s)[1].args, (std::vector<double>{2, 0.6}));
  EXPECT_EQ((*s)[2].args, (std::vector<double>{0.5, 0, 0}));
}

TEST(Scenario, RefusesBadFilesNamingTheEvent) {
  const std::pair<const char*, const char*> bad[] = {
      {"[]", "must be an object {\"events\""},
      {"{\"events\": [{\"at_s\": 1}]}", "events[0]: no \"fault\""},
      {"{\"events\": [{\"fault\": \"gps-loss\"}]}", "events[0]: no \"at_s\""},
      {"{\"events\": [{\"at_s\": 1, \"fault\": \"gps-loss\", \"then\": 2}]}", "unknown key 'then'"},
      {"{\"events\": [{\"at_s\": 1, \"fault\": \"gps-loss\", \"duration_s\": -1}]}", "events[0]: fault gps-loss: the duration"},
      {"{\"events\": [{\"at_s\": 1, \"fault\": \"motor\", \"args\": [1]}]}", "takes 2 arguments"},
      {"{\"events\": [{\"at_s\": \"1\", \"fault\": \"gps-loss\"}]}", "at_s: must be a number"},
      {"not json", "not JSON"},
  };
  for (const auto& [text, what] : bad) {
    auto s = parse_scenario(text, "scenario 'x.json'");
    ASSERT_FALSE(s) << text;
    EXPECT_NE(s.error().message.find("scenario 'x.json'"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find(what), std::string::npos) << text << ": " << s.error().message;
    EXPECT_EQ(s.error().kind, ErrorKind::Input) << text;
  }
  auto big = load_scenario("/dev/zero");
  ASSERT_FALSE(big);
  EXPECT_NE(big.error().message.find("larger than 1 MiB"), std::string::npos) << big.error().message;
}

TEST(FaultSchedule, StartsAndEndsAtSimulatedTimesAndFoldsWhatIsActive) {
  FaultSchedule s({*parse_fault("gps-loss@0.02+0.01"), *parse_fault("motor:2,0.5@0.012"), *parse_fault("hil-drop:0.5@0"),
                   *parse_fault("hil-drop:0.5@0"), *parse_fault("baro-drift:10@0.004")});
  std::vector<std::string> said;
  for (int k = 1; k <= 10; ++k)
    for (const auto& c : s.update(k * 0.004)) said.push_back(c.text());
  ASSERT_EQ(said.size(), 6u);
  EXPECT_EQ(said[0], "t=0.004 s fault hil-drop:0.5 started");
  EXPECT_EQ(said[3], "t=0.012 s fault motor:2,0.5 started");
  EXPECT_EQ(said[4], "t=0.020 s fault gps-loss started (0.01 s)");
  EXPECT_EQ(said[5], "t=0.032 s fault gps-loss ended");
  const auto& a = s.active();
  EXPECT_FALSE(a.gps_loss);
  EXPECT_DOUBLE_EQ(a.motor_effectiveness[2], 0.5);
  EXPECT_DOUBLE_EQ(a.hil_link.drop_p, 0.75);  // two independent drops: 1 - 0.5 * 0.5
  EXPECT_NEAR(a.baro_offset_Pa, 10 * (0.040 - 0.004), 1e-9);
  ASSERT_EQ(s.records().size(), 5u);
  EXPECT_EQ(s.records()[4].name, "gps-loss");
  EXPECT_DOUBLE_EQ(s.records()[4].start_s, 0.020);
  EXPECT_NEAR(*s.records()[4].end_s, 0.032, 1e-12);
  EXPECT_FALSE(s.records()[3].end_s);
}

TEST(Scenario, ConditionsStartAndEndFaultsOnAltitudeArmedModeAndAnotherEvent) {
  auto specs = parse_scenario(R"({"events": [
      {"id": "climb", "when": {"altitude_above_m": 5}, "fault": "gps-loss", "end_when": {"mode": "Land"}},
      {"when": {"after": "climb", "delay_s": 3}, "fault": "motor", "args": [2, 0.7], "duration_s": 4},
      {"at_s": 1, "when": {"armed": true}, "fault": "hil-delay", "args": [20], "end_when": {"armed": false}}]})",
                              "scenario 'c.json'");
  ASSERT_TRUE(specs) << specs.error().message;
  FaultSchedule schedule(*specs);
  VehicleObservation seen{0, false, "Hold"};
  EXPECT_TRUE(schedule.update(0.5, seen).empty());
  seen.armed = true;
  EXPECT_TRUE(schedule.update(0.9, seen).empty());  // armed, but not before at_s
  auto c = schedule.update(1.0, seen);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].spec.kind, FaultKind::HilDelay);
  seen.altitude_m = 5.5;
  c = schedule.update(4.0, seen);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].spec.kind, FaultKind::GpsLoss);
  seen.altitude_m = 2;  // the condition latched: it stays started
  EXPECT_TRUE(schedule.update(6.9, seen).empty());
  c = schedule.update(7.0, seen);  // 3 s after "climb"
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].spec.kind, FaultKind::Motor);
  EXPECT_DOUBLE_EQ(schedule.active().motor_effectiveness[2], 0.7);
  seen.mode = "Land";
  c = schedule.update(8.0, seen);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].started);
  EXPECT_EQ(c[0].spec.kind, FaultKind::GpsLoss);
  c = schedule.update(11.0, seen);  // the motor's 4 s from its start
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].spec.kind, FaultKind::Motor);
  seen.armed = false;
  c = schedule.update(12.0, seen);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].spec.kind, FaultKind::HilDelay);
  EXPECT_FALSE(c[0].started);
}

TEST(Scenario, RefusesBadConditionsNamingTheEvent) {
  auto bad = [](const std::string& events) {
    auto r = parse_scenario(R"({"events": [)" + events + "]}", "scenario 'c.json'");
    return r ? std::string("(parsed)") : r.error().message;
  };
  EXPECT_NE(bad(R"({"fault": "gps-loss"})").find("no \"at_s\""), std::string::npos);
  EXPECT_NE(bad(R"({"when": {}, "fault": "gps-loss"})").find("events[0].when: names nothing"), std::string::npos);
  EXPECT_NE(bad(R"({"when": {"altitude_above_m": "high"}, "fault": "gps-loss"})").find("events[0].when.altitude_above_m: must be a number"),
            std::string::npos);
  EXPECT_NE(bad(R"({"when": {"armed": 1}, "fault": "gps-loss"})").find("must be true or false"), std::string::npos);
  EXPECT_NE(bad(R"({"when": {"alt": 3}, "fault": "gps-loss"})").find("unknown key 'alt'"), std::string::npos);
  EXPECT_NE(bad(R"({"when": {"after": "nobody"}, "fault": "gps-loss"})").find("'nobody' is no other event's id"), std::string::npos);
  EXPECT_NE(bad(R"({"id": "a", "at_s": 1, "fault": "gps-loss"}, {"id": "a", "at_s": 2, "fault": "vio-loss"})").find("events[1].id: 'a'"),
            std::string::npos);
  EXPECT_NE(bad(R"({"when": {"armed": true, "delay_s": -1}, "fault": "gps-loss"})").find("delay_s: must be within 0..86400"),
            std::string::npos);
}

TEST(FaultSchedule, FaultsStartedAndClearedByHand) {
  auto live = parse_live_fault("motor:2,0.5");
  ASSERT_TRUE(live) << live.error().message;
  auto timed = parse_live_fault("gps-loss+2.5");
  ASSERT_TRUE(timed) << timed.error().message;
  EXPECT_DOUBLE_EQ(*timed->duration_s, 2.5);
  EXPECT_TRUE(parse_live_fault("imu-bias:1e+0,0,0"));  // an exponent's sign is no duration
  const auto at = parse_live_fault("gps-loss@3");
  ASSERT_FALSE(at);
  EXPECT_NE(at.error().message.find("starts now"), std::string::npos);
  const auto bad = parse_live_fault("motor:7,0.5");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message.find("@0"), std::string::npos) << bad.error().message;
  EXPECT_EQ(bad.error().kind, ErrorKind::Input);
  EXPECT_EQ(at.error().kind, ErrorKind::Input);

  FaultSchedule schedule;
  schedule.update(10.0);
  schedule.start_now(*live);
  schedule.start_now(*timed);
  auto c = schedule.update(10.004);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(schedule.records()[0].start_s, 10.004, 1e-9);
  EXPECT_DOUBLE_EQ(schedule.active().motor_effectiveness[2], 0.5);
  c = schedule.clear("motor", 11.0);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].started);
  EXPECT_DOUBLE_EQ(schedule.active().motor_effectiveness[2], 1.0);
  EXPECT_TRUE(schedule.active().gps_loss);
  c = schedule.update(12.504);  // 2.5 s from its start
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(schedule.active().gps_loss);
  EXPECT_TRUE(schedule.clear("", 13).empty());  // nothing left to clear
  // The records keep each fault's duration (the dashboard shows what is left of it).
  ASSERT_EQ(schedule.records().size(), 2u);
  EXPECT_FALSE(schedule.records()[0].duration_s);
  EXPECT_DOUBLE_EQ(schedule.records()[1].duration_s.value_or(0), 2.5);
}

// The catalogue as the dashboard's menu lists it: every fault in a group, and its example as typed
// starts it (the menu pre-fills it).
TEST(FaultSpec, EveryFaultHasAGroupAndAnExampleThatStartsIt) {
  for (const auto& f : fault_catalogue()) {
    SCOPED_TRACE(f.name);
    bool listed = false;
    for (const auto g : kFaultGroups) listed = listed || g == f.group;
    EXPECT_TRUE(listed);
    EXPECT_STRNE(to_string(f.group), "?");
    const auto spec = parse_live_fault(std::string(f.name) + f.example);
    ASSERT_TRUE(spec) << spec.error().message;
    EXPECT_EQ(spec->kind, f.kind);
    EXPECT_EQ(spec->args.size(), f.required_args) << "the example gives the required arguments";
  }
  EXPECT_EQ(info(FaultKind::HilDuplicate).group, FaultGroup::HilLink);
  EXPECT_EQ(info(FaultKind::ActuatorsStale).group, FaultGroup::Board);
  EXPECT_STREQ(info(FaultKind::Gust).example, ":5,0+6");  // needs a duration: its example has one
}

// Each kind has its entry in the catalogue (its case in the fold is a compile error when missing:
// -Werror=switch in engine/faults).
TEST(FaultSpec, EveryKindHasItsCatalogueEntry) {
  for (std::size_t k = 0; k < kFaultKinds; ++k) EXPECT_EQ(static_cast<std::size_t>(info(static_cast<FaultKind>(k)).kind), k) << k;
}

// A sensor unit's faults come from its folder (engine/sensors/rangefinder) through the catalogue,
// parse like the others and fold into the unit's own state.
TEST(FaultSpec, SensorUnitFaultsComeFromTheirUnitAndFoldIntoIt) {
  const FaultInfo* stuck = find_fault("rangefinder-stuck");
  const FaultInfo* none = find_fault("rangefinder-no-return");
  ASSERT_NE(stuck, nullptr);
  ASSERT_NE(none, nullptr);
  EXPECT_EQ(stuck->kind, FaultKind::SensorUnit);
  EXPECT_EQ(stuck->group, FaultGroup::OptionalSensors);
  EXPECT_NE(stuck->unit_fault, none->unit_fault);
  auto spec = parse_fault("rangefinder-no-return@2+3");
  ASSERT_TRUE(spec) << spec.error().message;
  EXPECT_EQ(spec->name(), "rangefinder-no-return");
  EXPECT_EQ(spec->text(), "rangefinder-no-return@2+3");
  auto bad = parse_fault("rangefinder-stuck:1");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("fault rangefinder-stuck: takes 0 arguments"), std::string::npos) << bad.error().message;
  FaultSchedule schedule({*spec, *parse_fault("rangefinder-stuck@4")});
  schedule.update(1.0);
  EXPECT_FALSE(std::get<sensors::Rangefinder::Faults>(schedule.active().units).no_return);
  schedule.update(2.0);
  EXPECT_TRUE(std::get<sensors::Rangefinder::Faults>(schedule.active().units).no_return);
  EXPECT_FALSE(std::get<sensors::Rangefinder::Faults>(schedule.active().units).stuck);
  schedule.update(4.0);
  EXPECT_TRUE(std::get<sensors::Rangefinder::Faults>(schedule.active().units).stuck);
  schedule.update(5.0);
  EXPECT_FALSE(std::get<sensors::Rangefinder::Faults>(schedule.active().units).no_return);  // its 3 s are over
  EXPECT_EQ(schedule.active_texts(), std::vector<std::string>{"rangefinder-stuck"});
}

}  // namespace
}  // namespace hitl::faults
