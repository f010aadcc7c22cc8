// The campaign's page (index.html) from synthetic results: hostile names escaped, a cell per
// trajectory and fault case with a link or mark per flight, the broken criteria in their cell, each
// criterion's min / median / max across the seeds, the history's trends with a regression flagged,
// the links chosen from what a flight's folder holds, and a size that grows linearly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/campaign/campaign_page.h"
#include "engine/campaign/criteria.h"
#include "engine/campaign/history.h"

namespace hitl::campaign {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = 0; (at = text.find(what, at)) != std::string::npos; at += what.size()) ++n;
  return n;
}

std::string temp_folder(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("hitl-page-test-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

Campaign campaign_of(std::vector<std::string> trajectories, std::vector<std::string> fault_cases, std::vector<uint64_t> seeds) {
  Campaign c;
  c.file = "c.toml";
  c.name = "page";
  for (const auto& t : trajectories) c.trajectories.push_back({t, t + ".json", "/x/" + t + ".json"});
  for (const auto& name : fault_cases) {
    FaultCase fc;
    fc.name = name;
    c.fault_cases.push_back(fc);
  }
  c.seeds = std::move(seeds);
  c.speeds = {0};
  Criterion rms;
  rms.name = "tracking-rms";
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

/// A flight's result as the runner writes it: its criteria judged on a summary with this RMS.
FlightResult result_of(const Campaign& c, const Flight& f, double rms_m, bool armed = false) {
  FlightResult r;
  r.index = f.index;
  r.id = f.id;
  r.name = f.name;
  r.verdicts = judge(c, {{"end", "trajectory_done"}, {"trajectory", {{"rms_m", rms_m}}}, {"stack", {{"armed", armed}}}});
  r.outcome = passed(r.verdicts) ? "passed" : "failed";
  r.summary_line = f.name + ": ended trajectory_done";
  r.wall_s = 1;
  return r;
}

/// The page's data (<script type="application/json" id="hitl-campaign-data">).
nlohmann::json page_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"hitl-campaign-data\">";
  const auto at = html.find(open);
  if (at == std::string::npos) return nullptr;
  const auto start = at + open.size();
  return nlohmann::json::parse(html.substr(start, html.find("</script>", start) - start));
}

PageInput input_of(const Campaign& c, const std::vector<Flight>& flights, const std::vector<std::optional<FlightResult>>& results) {
  PageInput in;
  in.campaign = &c;
  in.flights = &flights;
  in.results = &results;
  in.links.resize(flights.size());
  in.run.started_utc = "2026-11-29T12:00:00Z";
  in.run.hitl_version = "0.1.0";
  in.history_note = "kept out of the history";
  in.dygraphs_note = "no dygraphs in this test";
  return in;
}

TEST(CampaignPage, EscapesHostileNamesEverywhere) {
  auto c = campaign_of({"<script>alert(1)</script>"}, {"none"}, {1});
  c.name = "x\"><img src=y>";
  c.criteria[0].name = "<b>rms</b>";
  const auto flights = expand(c);
  std::vector<std::optional<FlightResult>> results(flights.size());
  results[0] = result_of(c, flights[0], 0.9);
  results[0]->summary_line = "</script><script>alert(2)</script>";
  results[0]->verdicts[1].message = "\"><script>alert(3)</script>";
  auto in = input_of(c, flights, results);
  in.run.label = "<i onmouseover=alert(4)>v1</i>";
  in.links[0] = "flights/\"><script>alert(5)</script>/report.html";
  report::DygraphsLibrary fake;
  fake.script = "/* dygraphs */";
  fake.stylesheet = ".dygraph{}";
  in.dygraphs = &fake;
  const std::string html = campaign_page_html(in);
  for (const char* raw : {"<script>alert", "<img src=y>", "<b>rms</b>", "<i onmouseover", "\"><script"})
    EXPECT_EQ(html.find(raw), std::string::npos) << raw;
  // The page's own scripts only: its data, dygraphs, its script.
  EXPECT_EQ(count(html, "<script"), 3u);
  EXPECT_EQ(count(html, "</script>"), 3u);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;i onmouseover=alert(4)&gt;v1&lt;/i&gt;"), std::string::npos);
  EXPECT_NE(html.find("/* dygraphs */"), std::string::npos);
  // The data holds the names as they are (a script reads them), '<' written as \u003c.
  const auto data = page_data(html);
  ASSERT_FALSE(data.is_null());
  EXPECT_EQ(data["cells"][0], "<script>alert(1)</script> / none");
  EXPECT_EQ(data["distributions"][0]["criterion"], "<b>rms</b>");
}

TEST(CampaignPage, ShowsTheMatrixWithAMarkPerFlightAndWhatEachBroke) {
  const auto c = campaign_of({"square", "hover"}, {"none", "gps-loss"}, {1, 2, 3});
  const auto flights = expand(c);
  ASSERT_EQ(flights.size(), 12u);
  std::vector<std::optional<FlightResult>> results(flights.size());
  for (const auto& f : flights) results[f.index] = result_of(c, f, 0.1 + 0.1 * static_cast<double>(f.seed));
  results[4] = result_of(c, flights[4], 0.75);  // square/gps-loss/seed-2 breaks tracking-rms
  results[7]->outcome = "error";                // hover/none/seed-2 crashed
  results[7]->reason = "killed by signal 9 (SIGKILL)";
  results[7]->verdicts.clear();
  results[11].reset();  // hover/gps-loss/seed-3 not flown
  auto in = input_of(c, flights, results);
  for (const auto& f : flights)
    if (f.index != 11) in.links[f.index] = "flights/" + f.id + "/report.html";
  const std::string html = campaign_page_html(in);
  // A cell per trajectory and fault case, a mark per flight: a link when it has one.
  EXPECT_EQ(count(html, "<td class=\"cell "), 4u);
  EXPECT_EQ(count(html, "class=\"flight "), 12u);
  EXPECT_EQ(count(html, "<a class=\"flight "), 11u);
  EXPECT_EQ(count(html, "href=\"flights/"), 11u);
  EXPECT_EQ(count(html, "<span class=\"flight missing\""), 1u);
  // Each cell coloured by its worst flight, its broken criteria as its text.
  const std::regex cell(R"re(<td class="cell (\w+)" data-cell="(\d)"[^>]*>([\s\S]*?)</td>)re");
  std::map<std::string, std::pair<std::string, std::string>> cells;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), cell); it != std::sregex_iterator(); ++it)
    cells[(*it)[2]] = {(*it)[1], (*it)[3]};
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells["0"].first, "passed");  // square/none
  EXPECT_EQ(cells["1"].first, "failed");  // square/gps-loss
  EXPECT_NE(cells["1"].second.find("seed 2: tracking-rms: trajectory.rms_m = 0.75, limit &lt;= 0.5"), std::string::npos)
      << cells["1"].second;
  EXPECT_EQ(cells["2"].first, "error");  // hover/none
  EXPECT_NE(cells["2"].second.find("seed 2: error: killed by signal 9 (SIGKILL)"), std::string::npos);
  EXPECT_EQ(cells["3"].first, "missing");  // hover/gps-loss: one not flown, none broken
  EXPECT_NE(cells["3"].second.find("seed 3: not flown"), std::string::npos);
  // The header's counts.
  EXPECT_NE(html.find("data-flights=\"12\" data-passed=\"9\" data-failed=\"1\" data-errors=\"1\" data-missing=\"1\""),
            std::string::npos);
  // Each criterion across the seeds: min / median / max of square/none's three flights.
  EXPECT_NE(html.find("<td>0.2 / 0.3 / 0.4</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"broken\">0.2 / 0.4 / 0.75 (1 broke it)</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>3 held</td>"), std::string::npos);  // disarmed: true/false, counted
  const auto data = page_data(html);
  ASSERT_EQ(data["distributions"].size(), 1u);  // tracking-rms; flown and disarmed have no number
  const auto& rows = data["distributions"][0]["rows"];
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], nlohmann::json({0.2, 0.30000000000000004, 0.4}));
  EXPECT_EQ(rows[3].size(), 3u);  // two of its flights flown: min, median, max of two
  // No history, no dygraphs: the page says so, and has no script but its data.
  EXPECT_NE(html.find("id=\"no-trends\""), std::string::npos);
  EXPECT_NE(html.find("id=\"no-plots\""), std::string::npos);
  EXPECT_EQ(count(html, "<script"), 1u);
}

TEST(CampaignPage, DrawsTheHistorysTrendsAndFlagsARegression) {
  const std::string dir = temp_folder("trends");
  const auto c = campaign_of({"hover"}, {"none"}, {1, 2});
  const auto flights = expand(c);
  const std::string history = dir + "/h.sqlite";
  for (const double rms_m : {0.10, 0.11, 0.12, 0.40}) {  // the last run much worse
    std::vector<std::optional<FlightResult>> results;
    for (const auto& f : flights) results.push_back(result_of(c, f, rms_m));
    ASSERT_TRUE(record_run(history, c, flights, results, {"v" + std::to_string(static_cast<int>(rms_m * 100)), "2026-11-29T12:00:00Z", 1, false}));
  }
  std::vector<std::optional<FlightResult>> results;
  for (const auto& f : flights) results.push_back(result_of(c, f, 0.40));
  ASSERT_TRUE(write_campaign_page(dir, c, flights, results, {"v40", "2026-11-29T12:00:00Z", "0.1.0", 2, false, false, {}}, history));
  std::ifstream in(dir + "/" + kPageFile);
  std::stringstream s;
  s << in.rdbuf();
  const std::string html = s.str();
  EXPECT_NE(html.find("<table id=\"trends\">"), std::string::npos);
  EXPECT_EQ(html.find("id=\"no-trends\""), std::string::npos);
  const auto data = page_data(html);
  ASSERT_EQ(data["trends"].size(), 3u);  // flown, tracking-rms, disarmed
  const auto& rms = data["trends"][1];
  EXPECT_EQ(rms["criterion"], "tracking-rms");
  EXPECT_TRUE(rms["regression"].get<bool>());
  EXPECT_EQ(rms["runs"].size(), 4u);
  EXPECT_EQ(rms["series"], nlohmann::json({"mean", "worst", "broke it"}));
  EXPECT_NEAR(rms["rows"][3][0].get<double>(), 0.40, 1e-9);
  EXPECT_FALSE(data["trends"][2]["regression"].get<bool>());
  EXPECT_EQ(data["trends"][2]["series"], nlohmann::json({"broke it"}));  // an equals criterion: by its failures
  // The row of the regression is marked, with `hitl campaign history`'s verdict.
  EXPECT_NE(html.find("<tr class=\"regression\" data-criterion=\"tracking-rms\">"), std::string::npos);
  EXPECT_NE(html.find("REGRESSION: mean 0.4 against 0.11"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(CampaignPage, LinksEachFlightToItsReportElseItsSummaryElseItsLog) {
  const std::string dir = temp_folder("links");
  EXPECT_EQ(flight_link(dir, "flights/x"), "");
  std::ofstream(dir + "/log.txt") << "log";
  EXPECT_EQ(flight_link(dir, "flights/x"), "flights/x/log.txt");
  std::ofstream(dir + "/summary.json") << "{}";
  EXPECT_EQ(flight_link(dir, "flights/x"), "flights/x/summary.json");
  std::ofstream(dir + "/report.html") << "<html></html>";
  EXPECT_EQ(flight_link(dir, "flights/x"), "flights/x/report.html");
  std::filesystem::remove_all(dir);
}

TEST(CampaignPage, GrowsLinearlyWithTheFlights) {
  auto size_of = [](std::size_t seeds) {
    std::vector<uint64_t> s;
    for (uint64_t i = 1; i <= seeds; ++i) s.push_back(i);
    const auto c = campaign_of({"square", "figure-eight", "hover"}, {"none", "gps-loss", "weak-motor", "gust"}, s);
    const auto flights = expand(c);
    std::vector<std::optional<FlightResult>> results;
    for (const auto& f : flights) results.push_back(result_of(c, f, f.seed % 7 == 0 ? 0.9 : 0.2));
    auto in = input_of(c, flights, results);
    for (const auto& f : flights) in.links[f.index] = "flights/" + f.id + "/report.html";
    return campaign_page_html(in).size();
  };
  const std::size_t small = size_of(3), large = size_of(30);  // 36 and 360 flights
  // Per flight about 400 bytes (its link and title, its figures' share of the data), a broken one more.
  const double per_flight = static_cast<double>(large - small) / (360 - 36);
  EXPECT_LT(per_flight, 1000) << small << " bytes for 36 flights, " << large << " for 360";
  EXPECT_LT(large, 400'000u);
  std::cout << "page without dygraphs: " << small << " bytes for 36 flights, " << large << " for 360 (" << per_flight
            << " bytes a flight)\n";
}

}  // namespace
}  // namespace hitl::campaign
