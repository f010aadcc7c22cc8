// Issue 34, bounds on what combines: stacked scales stay within one fault's range, at most
// kMaxActiveFaults active at once (refused at load, or when due), scenario events that wait on each
// other refused naming them, and deep or out-of-range JSON an input error, not a crash.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/faults/fault_schedule.h"
#include "engine/faults/scenario.h"

namespace hitl::faults {
namespace {

FaultSpec fault(const std::string& text) {
  auto spec = parse_fault(text);
  EXPECT_TRUE(spec.ok()) << text;
  return *spec;
}

TEST(FaultBounds, StackedScalesStayWithinOneFaultsRange) {
  FaultSchedule schedule({fault("motor:0,2"), fault("motor:0,2"), fault("motor:0,2"), fault("imu-noise:100"), fault("imu-noise:100"),
                          fault("mag-scale:10"), fault("mag-scale:10"), fault("gps-noise:50"), fault("gps-noise:50"), fault("motor:1,0.5"),
                          fault("motor:1,0.5")});
  schedule.update(0);
  const auto& a = schedule.active();
  EXPECT_EQ(a.motor_effectiveness[0], 2.0);
  EXPECT_EQ(a.motor_effectiveness[1], 0.25);  // weakening still multiplies
  EXPECT_EQ(a.imu_noise_scale, 100.0);
  EXPECT_EQ(a.mag_scale, 10.0);
  EXPECT_EQ(a.gps_noise_scale, 100.0);
}

TEST(FaultBounds, MoreThanTheLimitActiveAtOnceIsRefusedAtLoad) {
  std::vector<FaultSpec> specs(kMaxActiveFaults, fault("gps-loss@0+10"));
  EXPECT_TRUE(check_active_limit(specs).ok());
  specs.push_back(fault("gps-loss@10+5"));  // starts as the others end: no overlap
  EXPECT_TRUE(check_active_limit(specs).ok());
  specs.push_back(fault("gps-loss@5"));
  auto r = check_active_limit(specs);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::Input);
  EXPECT_EQ(r.error().message, "at most 64 faults can be active at once; 65 could be at t=5 s");
}

TEST(FaultBounds, AFaultDueAtTheLimitIsRefusedWhenItComes) {
  FaultSchedule schedule(std::vector<FaultSpec>(kMaxActiveFaults, fault("gps-loss")));
  schedule.update(0);
  EXPECT_EQ(schedule.active_count(), kMaxActiveFaults);
  schedule.start_now(fault("motor:0,0.5"));
  const auto changes = schedule.update(0.1);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_TRUE(changes[0].refused);
  EXPECT_EQ(changes[0].text(), "t=0.100 s fault motor:0,0.5 refused: 64 faults are active, the limit");
  EXPECT_EQ(schedule.active_count(), kMaxActiveFaults);
  EXPECT_EQ(schedule.active().motor_effectiveness[0], 1.0);
}

TEST(FaultBounds, ScenarioEventsThatWaitOnEachOtherAreRefusedNamed) {
  const std::string text = R"({"events": [{"id": "x", "at_s": 1, "fault": "gps-loss"},
      {"id": "p", "when": {"after": "q"}, "fault": "mag-stuck"},
      {"id": "q", "when": {"after": "p"}, "fault": "baro-stuck"},
      {"when": {"after": "p"}, "fault": "vio-loss"}]})";
  auto r = parse_scenario(text, "scenario 's.json'");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::Input);
  EXPECT_EQ(r.error().message, "scenario 's.json': events 'p', 'q' wait on each other ('p' after 'q', 'q' after 'p'): none would start");
  // A chain is fine; so is ending after another.
  EXPECT_TRUE(parse_scenario(R"({"events": [{"id": "a", "at_s": 1, "fault": "gps-loss"},
      {"id": "b", "when": {"after": "a"}, "fault": "mag-stuck", "end_when": {"after": "c"}},
      {"id": "c", "when": {"after": "b"}, "fault": "baro-stuck", "end_when": {"after": "b"}}]})",
                             "s")
                  .ok());
}

TEST(FaultBounds, DeepOrOutOfRangeScenarioJsonIsAnInputError) {
  const std::string deep = R"({"events": [)" + std::string(100000, '[') + std::string(100000, ']') + "]}";
  auto r = parse_scenario(deep, "scenario 'deep.json'");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().kind, ErrorKind::Input);
  EXPECT_EQ(r.error().message, "scenario 'deep.json': is nested deeper than 32 levels (at byte 42)");
  auto big = parse_scenario(R"({"events": [{"at_s": 1e400, "fault": "gps-loss"}]})", "scenario 'big.json'");
  ASSERT_FALSE(big.ok());
  EXPECT_EQ(big.error().kind, ErrorKind::Input);
  EXPECT_NE(big.error().message.find("number overflow"), std::string::npos) << big.error().message;
  // Brackets inside strings do not count; an error shows at most a line of the value.
  auto bad = parse_scenario(R"({"description": "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[", "events": [[1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23]]})",
                            "s");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "s: events[0]: must be an object {\"at_s\", \"fault\", ...} (got [1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23...)");
}

}  // namespace
}  // namespace hitl::faults
