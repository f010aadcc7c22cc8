// The history: runs stored and read back as per-criterion trends; a figure worse than the runs
// before it by more than their spread is a regression, one within it is not.
#include <gtest/gtest.h>

#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/campaign/history.h"

namespace hitl::campaign {
namespace {

class HistoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("hitl-history-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    path_ = (dir_ / "sub" / "h.sqlite").string();  // its folder is made too
    c_.name = "c";
    c_.trajectories = {{"hover", "hover.json", "/x/hover.json"}};
    FaultCase none;
    none.name = "none";
    c_.fault_cases = {none};
    c_.seeds = {1, 2};
    c_.speeds = {0};
    flights_ = expand(c_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// A run whose two flights measured rms_a and rms_b against "<= 1".
  void record(double rms_a, double rms_b, const std::string& label) {
    std::vector<std::optional<FlightResult>> results;
    for (const double rms : {rms_a, rms_b}) {
      FlightResult r;
      r.index = results.size();
      r.id = flights_[r.index].id;
      r.outcome = rms <= 1 ? "passed" : "failed";
      Verdict v;
      v.criterion = "tracking";
      v.figure = "trajectory.rms_m";
      v.limit = "<= 1";
      v.value = rms;
      v.ok = rms <= 1;
      r.verdicts = {v};
      results.push_back(r);
    }
    ASSERT_TRUE(record_run(path_, c_, flights_, results, RunRecord{label, "2026-11-29T00:00:00Z", 1.0, false}));
  }

  std::filesystem::path dir_;
  std::string path_;
  Campaign c_;
  std::vector<Flight> flights_;
};

TEST_F(HistoryTest, AFigureWorseThanTheSpreadOfTheRunsBeforeIsARegression) {
  record(0.10, 0.12, "v1");
  record(0.11, 0.13, "v2");
  auto early = read_history(path_, "c", 10);
  ASSERT_TRUE(early) << early.error().message;
  ASSERT_EQ(early->trends.size(), 1u);
  EXPECT_FALSE(early->trends[0].regression);
  EXPECT_EQ(early->trends[0].verdict, "fewer than 3 runs: no trend yet");
  record(0.115, 0.125, "v3");  // within the spread of v1 and v2 (means 0.11 and 0.12)
  auto steady = read_history(path_, "c", 10);
  ASSERT_TRUE(steady);
  EXPECT_FALSE(steady->trends[0].regression) << steady->trends[0].verdict;
  record(0.30, 0.40, "v4");  // far outside it
  auto h = read_history(path_, "c", 10);
  ASSERT_TRUE(h);
  EXPECT_EQ(h->runs, 4u);
  const auto& t = h->trends[0];
  ASSERT_EQ(t.points.size(), 4u);
  EXPECT_EQ(t.points.front().label, "v1");  // oldest first
  EXPECT_EQ(t.points.back().label, "v4");
  EXPECT_DOUBLE_EQ(t.points.back().mean, 0.35);
  EXPECT_DOUBLE_EQ(t.points.back().worst, 0.40);
  EXPECT_TRUE(t.regression) << t.verdict;
  EXPECT_EQ(t.verdict.rfind("REGRESSION: mean 0.35 against", 0), 0u) << t.verdict;
  auto last_two = read_history(path_, "c", 2);
  ASSERT_TRUE(last_two);
  EXPECT_EQ(last_two->trends[0].points.size(), 2u);
  auto names = history_campaigns(path_);
  ASSERT_TRUE(names);
  EXPECT_EQ(*names, std::vector<std::string>{"c"});
}

TEST_F(HistoryTest, ForAMinimumLowerIsWorse) {
  Trend t;
  t.limit = ">= 240";
  for (const double mean : {250.0, 251.0, 249.0}) {
    TrendPoint p;
    p.flights = 1;
    p.mean = mean;
    t.points.push_back(p);
  }
  judge_trend(t);
  EXPECT_TRUE(t.regression) << t.verdict;  // 249 below 250..251 by more than 1? 250.5 - 249 = 1.5 > 1
  t.points.back().mean = 260;
  judge_trend(t);
  EXPECT_FALSE(t.regression) << t.verdict;
}

TEST_F(HistoryTest, AnotherFileIsRefusedNotWritten) {
  std::ofstream(dir_ / "junk.sqlite") << "not a database, not at all";
  std::vector<std::optional<FlightResult>> none(flights_.size());
  auto r = record_run((dir_ / "junk.sqlite").string(), c_, flights_, none, RunRecord{});
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("junk.sqlite"), std::string::npos) << r.error().message;
  auto missing = read_history((dir_ / "absent.sqlite").string(), "c", 5);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::Input);
  record(0.1, 0.1, "v1");
  auto other = read_history(path_, "other", 5);
  ASSERT_FALSE(other);
  EXPECT_NE(other.error().message.find("no runs of campaign \"other\""), std::string::npos);
}

TEST_F(HistoryTest, ARunRecordsItsFlightStackAndPx4sVersion) {
  record(0.10, 0.12, "v1");  // the emulated board: no version
  c_.stack = Stack::Px4;
  c_.px4.emplace();
  c_.px4->build = px4::Px4Build{};
  c_.px4->build->version = "v1.16.0";
  record(0.11, 0.13, "v2");
  auto h = read_history(path_, "c", 10);
  ASSERT_TRUE(h) << h.error().message;
  ASSERT_EQ(h->trends.size(), 1u);
  ASSERT_EQ(h->trends[0].points.size(), 2u);
  EXPECT_EQ(h->trends[0].points[0].stack_version, "");
  EXPECT_EQ(h->trends[0].points[1].stack_version, "v1.16.0");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT stack, stack_version FROM runs ORDER BY id", -1, &s, nullptr), SQLITE_OK);
  std::vector<std::string> rows;
  while (sqlite3_step(s) == SQLITE_ROW)
    rows.push_back(std::string(reinterpret_cast<const char*>(sqlite3_column_text(s, 0))) + " " +
                   reinterpret_cast<const char*>(sqlite3_column_text(s, 1)));
  sqlite3_finalize(s);
  sqlite3_close(db);
  EXPECT_EQ(rows, (std::vector<std::string>{"target ", "px4 v1.16.0"}));
}

TEST_F(HistoryTest, AHistoryOfSchemaOneGainsTheStackAndKeepsItsRuns) {
  std::filesystem::create_directories(std::filesystem::path(path_).parent_path());
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
  // The tables as schema 1 made them, with one run.
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT); INSERT INTO meta VALUES('schema', '1');"
                         "CREATE TABLE runs(id INTEGER PRIMARY KEY AUTOINCREMENT, campaign TEXT NOT NULL, file TEXT, label TEXT,"
                         " started_utc TEXT, wall_s REAL, flights INTEGER, passed INTEGER, failed INTEGER, errors INTEGER,"
                         " missing INTEGER, stopped INTEGER);"
                         "CREATE TABLE flights(run INTEGER NOT NULL, flight_id TEXT, name TEXT, outcome TEXT, reason TEXT);"
                         "CREATE TABLE verdicts(run INTEGER NOT NULL, flight_id TEXT, criterion TEXT, figure TEXT, limit_text TEXT,"
                         " value REAL, ok INTEGER);"
                         "INSERT INTO runs(campaign, label, started_utc, flights) VALUES('c', 'old', '2026-11-28T00:00:00Z', 2);"
                         "INSERT INTO verdicts VALUES(1, 'x', 'tracking', 'trajectory.rms_m', '<= 1', 0.1, 1);",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  auto before = read_history(path_, "c", 10);  // read only: schema 1 as it is
  ASSERT_TRUE(before) << before.error().message;
  EXPECT_EQ(before->runs, 1u);
  record(0.11, 0.13, "new");  // written: schema 2
  auto after = read_history(path_, "c", 10);
  ASSERT_TRUE(after) << after.error().message;
  EXPECT_EQ(after->runs, 2u);
  ASSERT_EQ(after->trends.size(), 1u);
  ASSERT_EQ(after->trends[0].points.size(), 2u);
  EXPECT_EQ(after->trends[0].points[0].label, "old");
}

}  // namespace
}  // namespace hitl::campaign
