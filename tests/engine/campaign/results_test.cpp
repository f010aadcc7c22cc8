// Criteria judged on a summary, and the JUnit XML: suites per axis value, failures with figure and limit.
#include <gtest/gtest.h>

#include "engine/campaign/criteria.h"
#include "engine/campaign/results.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace hitl::campaign {
namespace {

Campaign campaign_with_criteria() {
  Campaign c;
  c.name = "c";
  c.trajectories = {{"hover", "hover.json", "/x/hover.json"}};
  FaultCase none;
  none.name = "none";
  c.fault_cases = {none};
  c.seeds = {1, 2};
  c.speeds = {0};
  Criterion rms;
  rms.name = "tracking";
  rms.figure = "trajectory.rms_m";
  rms.limit = 0.5;
  Criterion disarmed;
  disarmed.name = "disarmed";
  disarmed.figure = "stack.armed";
  disarmed.comparison = Comparison::Equals;
  disarmed.equals_bool = false;
  c.criteria = {rms, disarmed};
  return c;
}

TEST(CampaignCriteria, EachHoldsOrSaysTheFigureAndItsLimit) {
  const auto c = campaign_with_criteria();
  nlohmann::json summary = {{"end", "trajectory_done"}, {"trajectory", {{"rms_m", 0.75}}}, {"stack", {{"armed", false}}}};
  const auto v = judge(c, summary);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_TRUE(v[0].ok);  // flown
  EXPECT_FALSE(v[1].ok);
  EXPECT_EQ(v[1].message, "trajectory.rms_m = 0.75, limit <= 0.5");
  EXPECT_TRUE(v[2].ok);
  EXPECT_FALSE(passed(v));
  summary["end"] = "trajectory_failed";
  summary["trajectory"]["failure"] = "no takeoff";
  summary.erase("stack");
  const auto w = judge(c, summary);
  EXPECT_EQ(w[0].message, "end = trajectory_failed, limit == trajectory_done (no takeoff)");
  EXPECT_EQ(w[2].message, "stack.armed = absent, limit == false");
}

TEST(CampaignCriteria, ExpectationsLookForTheEventAfterTheFaultsStart) {
  Campaign c;
  Expectation says;
  says.name = "says-landing";
  says.kind = ExpectKind::Statustext;
  says.pattern = "Landing (detected|at)";
  says.after_fault = "gps-loss";
  says.within_s = 3;
  Expectation lands;
  lands.name = "lands";
  lands.kind = ExpectKind::Mode;
  lands.pattern = "Land";
  c.expectations = {says, lands};
  nlohmann::json summary = {
      {"end", "trajectory_done"},
      {"flight", {{"faults", {"gps-loss@10+2"}}}},
      {"faults", {{{"name", "gps-loss"}, {"start_s", 10.0}, {"end_s", 12.0}}}},
      {"events", {{{"t_s", 9.0}, {"source", "system 1"}, {"text", "Landing at current position"}},   // before the fault
                  {{"t_s", 11.0}, {"source", "simulator"}, {"text", "Landing detected"}},            // not the flight stack
                  {{"t_s", 12.5}, {"source", "system 1"}, {"text", "mode Land"}},
                  {{"t_s", 14.0}, {"source", "system 1"}, {"text", "Landing detected"}}}}};          // past 3 s
  auto v = judge(c, summary);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_FALSE(v[1].ok);
  EXPECT_EQ(v[1].limit, "statustext ~ /Landing (detected|at)/ within 3 s of gps-loss's start at 10.000 s");
  EXPECT_EQ(v[1].message, "no statustext ~ /Landing (detected|at)/ within 3 s of gps-loss's start at 10.000 s");
  EXPECT_TRUE(v[2].ok);
  EXPECT_EQ(v[2].value["t_s"], 12.5);
  summary["events"].push_back({{"t_s", 12.9}, {"source", "system 1"}, {"text", "Landing detected"}});
  EXPECT_TRUE(judge(c, summary)[1].ok);
  // A flight without that fault does not judge it; one whose fault never started fails it.
  nlohmann::json calm = {{"end", "trajectory_done"}, {"flight", {{"faults", nlohmann::json::array()}}},
                         {"faults", nlohmann::json::array()}, {"events", summary["events"]}};
  const auto calm_verdicts = judge(c, calm);
  ASSERT_EQ(calm_verdicts.size(), 2u);
  EXPECT_EQ(calm_verdicts[1].criterion, "lands");
  calm["flight"]["faults"] = {"gps-loss@100"};
  const auto late = judge(c, calm);
  ASSERT_EQ(late.size(), 3u);
  EXPECT_FALSE(late[1].ok);
  EXPECT_EQ(late[1].message, "the fault gps-loss never started, so statustext ~ /Landing (detected|at)/ could not follow it");
}

TEST(CampaignResults, JunitHasASuitePerAxisValueAndAFailurePerBrokenCriterion) {
  const auto c = campaign_with_criteria();
  const auto flights = expand(c);
  FlightResult ok;
  ok.index = 0;
  ok.outcome = "passed";
  ok.summary_line = "hover/none/seed-1: fine";
  FlightResult bad;
  bad.index = 1;
  bad.outcome = "failed";
  bad.summary_line = "hover/none/seed-2: <bad> & worse";
  Verdict v;
  v.criterion = "tracking";
  v.figure = "trajectory.rms_m";
  v.value = 0.75;
  v.limit = "<= 0.5";
  v.message = "trajectory.rms_m = 0.75, limit <= 0.5";
  bad.verdicts = {v};
  const auto xml = junit_xml(c, flights, {ok, bad});
  EXPECT_NE(xml.find("<testsuite name=\"trajectory=hover\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\""),
            std::string::npos) << xml;
  EXPECT_NE(xml.find("<testsuite name=\"faults=none\" tests=\"2\" failures=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testsuite name=\"seed=1\" tests=\"1\" failures=\"0\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testsuite name=\"seed=2\" tests=\"1\" failures=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"tracking: trajectory.rms_m = 0.75, limit &lt;= 0.5\" type=\"tracking\""),
            std::string::npos) << xml;
  EXPECT_NE(xml.find("<system-out>hover/none/seed-2: &lt;bad&gt; &amp; worse</system-out>"), std::string::npos) << xml;
  const auto missing = junit_xml(c, flights, {ok, std::nullopt});
  EXPECT_NE(missing.find("<skipped message="), std::string::npos) << missing;
  const auto t = tally({ok, std::nullopt});
  EXPECT_EQ(t.passed, 1u);
  EXPECT_EQ(t.missing, 1u);
}

}  // namespace
}  // namespace hitl::campaign

namespace hitl::campaign {
namespace {

TEST(CampaignResults, ADamagedResultFileIsAnErrorNotACrash) {
  const auto dir = std::filesystem::temp_directory_path() / ("hitl-result-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  FlightResult r;
  r.index = 3;
  r.id = "0123456789ab";
  r.outcome = "failed";
  r.verdicts.push_back(Verdict{"tracking", "trajectory.rms_m", false, 0.75, "<= 0.5", "trajectory.rms_m = 0.75, limit <= 0.5"});
  ASSERT_TRUE(write_result(dir.string(), r));
  auto back = read_result(dir.string());
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->index, 3u);
  EXPECT_EQ(back->verdicts.at(0).message, "trajectory.rms_m = 0.75, limit <= 0.5");
  std::ofstream(dir / "result.json") << R"({"index": "three", "outcome": "passed"})";
  auto damaged = read_result(dir.string());
  ASSERT_FALSE(damaged);
  EXPECT_EQ(damaged.error().kind, ErrorKind::Input);
  EXPECT_NE(damaged.error().message.find("result.json: not a flight result"), std::string::npos) << damaged.error().message;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace hitl::campaign
