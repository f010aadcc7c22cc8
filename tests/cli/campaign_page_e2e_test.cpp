// The campaign's page (DIR/index.html) through the real binary: a small lockstep campaign (two
// short hovers, one named with HTML's special characters, x no fault and a GPS loss x 2 seeds) with
// a planted criterion that the longer hover's flights break; then collect adds a second run to the
// history. In headless Chromium the page's script runs without an error and draws every plot; the
// matrix has a cell per trajectory and fault case and a link per flight, each to a file that exists;
// the failing flights' cells are marked failed with the criterion's text. And `hitl demo --campaign`.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "tests/support/chromium.h"
#include "tests/support/json_lines.h"
#include "tests/support/process.h"
#include "tests/support/tools.h"

namespace hitl {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// A hover of `hover_s` seconds at 2 m.
void write_hover(const std::string& path, double hover_s) {
  std::ofstream(path) << R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}, {"t": )" << hover_s
                      << R"(, "x": 0, "y": 0, "z": 2, "yaw": 0}]})";
}

/// Reads the page's matrix, the failing cells' texts, its plots and what the cursor shows over the
/// first plot's middle.
constexpr const char* kPageProbe = R"(out.ids=r?r.ids:null;
out.cells=document.querySelectorAll('#matrix td.cell').length;
out.flights=document.querySelectorAll('#matrix .flight').length;
out.links=Array.prototype.map.call(document.querySelectorAll('#matrix a.flight'),function(a){return a.getAttribute('href')});
out.failed_cells=Array.prototype.map.call(document.querySelectorAll('#matrix td.cell.failed'),function(td){return td.textContent});
out.failed_flights=document.querySelectorAll('#matrix a.flight.failed').length;
out.canvases=Array.prototype.filter.call(document.querySelectorAll('figure.plot canvas'),function(c){return c.width>0&&c.height>0}).length;
out.figures=document.querySelectorAll('figure.plot').length;
var g=r.graphs[0],a=g.getArea(),c=g.mouseEventElement_,b=c.getBoundingClientRect();
c.dispatchEvent(new MouseEvent('mousemove',{clientX:b.left+a.x+a.w/2,clientY:b.top+a.y+a.h/2,bubbles:true}));
out.hover=document.querySelector('#'+r.ids[0]+' .values').textContent;)";

TEST(CampaignPageE2E, TheResultsPageShowsEveryFlightAndWhatFailedInChromium) {
  const auto dir = test::temp_dir();
  write_hover(dir + "/short.json", 2);
  write_hover(dir + "/long<b>&.json", 8);
  const std::string file = dir + "/c.toml";
  // The short hover flies 25.0 s simulated, the long one 31.0 s: `planted` fails the long one's 4 flights.
  std::ofstream(file) << "[campaign]\nname = \"page\"\ntime_limit_s = 120\nreport = true\n"
                         "[matrix]\ntrajectories = [\"short.json\", \"long<b>&.json\"]\nseeds = [1, 2]\n"
                         "[faults]\nnone = []\ngps-loss = [\"gps-loss@2+2\"]\n"
                         "[criteria]\ndisarmed = { figure = \"stack.armed\", equals = false }\n"
                         "planted = { figure = \"sim_time_s\", max = 28 }\n";
  const std::string out = dir + "/out", history = dir + "/h.sqlite";
  auto r = test::run_hitl({"campaign", "run", file, "-j", "2", "--out", out, "--history", history, "--label", "first"},
                          std::chrono::seconds(120));
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;  // the planted criterion
  EXPECT_NE(r.out.find("campaign page: 8 flights: 4 passed, 4 failed, 0 errors, 0 not flown"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("page: " + out + "/index.html"), std::string::npos) << r.out;
  // collect writes the page again, with a second run in the history: two points per trend.
  auto collected = test::run_hitl({"campaign", "collect", file, "--out", out, "--history", history, "--label", "again"});
  ASSERT_EQ(collected.exit_code, 1) << collected.out << collected.err;
  const std::string page_path = out + "/index.html";
  ASSERT_TRUE(fs::exists(page_path));
  const std::string page = test::read_text(page_path);
  std::cout << "index.html: " << page.size() << " bytes for 8 flights\n";
  // Every flight's link, to its report (report = true), which exists.
  const auto summary = json::parse(test::read_text(out + "/summary.json"));
  std::set<std::string> expected_links;
  for (const auto& f : summary["results"]) expected_links.insert(f["folder"].get<std::string>() + "/report.html");
  ASSERT_EQ(expected_links.size(), 8u);
  EXPECT_NE(page.find("<th>long&lt;b&gt;&amp;</th>"), std::string::npos) << "the trajectory's name, escaped";
  EXPECT_EQ(page.find("long<b>"), std::string::npos);
  EXPECT_NE(page.find("<table id=\"trends\">"), std::string::npos);

  std::string why_not;
  bool required = false;
  const std::string chromium = test::find_chromium(why_not, required);
  if (chromium.empty()) {
    if (required) FAIL() << why_not;
    GTEST_SKIP() << why_not;
  }
  const auto probe = test::probe_in_chromium(chromium, page_path, dir, kPageProbe, "hitlCampaign");
  ASSERT_FALSE(probe.contains("failure")) << probe.dump();
  EXPECT_EQ(probe["errors"].size(), 0u) << probe["errors"].dump();
  EXPECT_EQ(probe["cells"], 4);
  EXPECT_EQ(probe["flights"], 8);
  std::set<std::string> links;
  for (const auto& link : probe["links"]) {
    links.insert(link.get<std::string>());
    EXPECT_TRUE(fs::is_regular_file(out + "/" + link.get<std::string>())) << link;
  }
  EXPECT_EQ(links, expected_links);
  // The long hover's two cells, each with its two flights failed and the criterion's words.
  ASSERT_EQ(probe["failed_cells"].size(), 2u) << probe.dump();
  EXPECT_EQ(probe["failed_flights"], 4);
  for (const auto& text : probe["failed_cells"]) {
    EXPECT_NE(text.get<std::string>().find("seed 1: planted: sim_time_s = 31.008, limit <= 28"), std::string::npos) << text;
    EXPECT_NE(text.get<std::string>().find("seed 2: planted: sim_time_s = 31.008, limit <= 28"), std::string::npos) << text;
  }
  // A plot of `planted`'s figure across the seeds, and a trend per criterion (flown, disarmed, planted), each drawn.
  ASSERT_EQ(probe["ids"], json({"dist-2", "trend-0", "trend-1", "trend-2"})) << probe.dump();
  EXPECT_EQ(probe["figures"], 4);
  EXPECT_GE(probe["canvases"].get<int>(), 4);
  EXPECT_NE(probe["hover"].get<std::string>().find("median"), std::string::npos) << probe["hover"];
}

// hitl demo --campaign: the built-in small campaign flown into a new demo folder, its page last.
TEST(CampaignPageE2E, DemoCampaignFliesTheSmallCampaignAndPrintsItsPage) {
  const auto tmp = test::temp_dir();
  const char* before = std::getenv("TMPDIR");
  const std::string saved = before ? before : "";
  ::setenv("TMPDIR", tmp.c_str(), 1);
  auto r = test::run_hitl({"--json", "demo", "--campaign"}, std::chrono::seconds(120));
  if (saved.empty()) ::unsetenv("TMPDIR");
  else ::setenv("TMPDIR", saved.c_str(), 1);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto lines = test::json_lines(r.out);
  ASSERT_FALSE(lines.empty());
  const auto& first = lines.front();
  EXPECT_EQ(first["type"], "status");
  EXPECT_EQ(first["event"], "campaign");
  const std::string page = first["page"];
  EXPECT_EQ(page.rfind(tmp + "/hitl-demo-", 0), 0u) << page;
  EXPECT_TRUE(fs::is_regular_file(page)) << page;
  const auto& summary = lines.back();
  EXPECT_EQ(summary["type"], "summary");
  EXPECT_EQ(summary["campaign"], "small");
  EXPECT_EQ(summary["flights"], 4);
  EXPECT_EQ(summary["passed"], 4);
  // Without --json the page's path is the last line.
  ::setenv("TMPDIR", tmp.c_str(), 1);
  auto text = test::run_hitl({"-q", "demo", "--campaign"}, std::chrono::seconds(120));
  if (saved.empty()) ::unsetenv("TMPDIR");
  else ::setenv("TMPDIR", saved.c_str(), 1);
  ASSERT_EQ(text.exit_code, 0) << text.out << text.err;
  const auto out_lines = test::lines_of(text.out);
  ASSERT_FALSE(out_lines.empty());
  EXPECT_TRUE(std::regex_match(out_lines.back(), std::regex(".*/hitl-demo-[^/]{6}/results/index\\.html"))) << text.out;
  EXPECT_TRUE(fs::is_regular_file(out_lines.back())) << out_lines.back();
}

}  // namespace
}  // namespace hitl
