// hitl campaign run through the real binary: a small campaign (4 short hovers at -j 2) writes its
// results folder; its JUnit XML read back by a real consumer (python3-junitparser) has every flight,
// suite and failure; the same flight alone gives the same figures (lockstep); kill -9 of one flight
// fails only that flight, with the reason; Ctrl-C then --resume flies only what is missing.
#include <gtest/gtest.h>

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"
#include "tests/support/tools.h"

namespace hitl {
namespace {

using nlohmann::json;

using test::read_text;

json read_json(const std::string& path) { return json::parse(read_text(path)); }

/// A folder with a hover of `hover_s` seconds and a campaign over it (2 fault cases x 2 seeds). The
/// runs' default history goes into it too (XDG_DATA_HOME), never the user's data folder.
std::string write_campaign(const std::string& dir, double hover_s, const std::string& extra_criteria,
                           double time_limit_s = 120, const std::string& campaign_keys = "") {
  ::setenv("XDG_DATA_HOME", dir.c_str(), 1);
  std::ofstream(dir + "/hover.json") << R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}, {"t": )" << hover_s
                                     << R"(, "x": 0, "y": 0, "z": 2, "yaw": 0}]})";
  const std::string file = dir + "/c.toml";
  std::ofstream(file) << "[campaign]\nname = \"e2e\"\ntime_limit_s = " << time_limit_s << "\n" << campaign_keys
                      << "[matrix]\ntrajectories = [\"hover.json\"]\nseeds = [1, 2]\n"
                         "[faults]\nnone = []\ngps-loss = [\"gps-loss@2+2\"]\n"
                         "[criteria]\ndisarmed = { figure = \"stack.armed\", equals = false }\n"
                      << extra_criteria
                      << "[expect]\nlands = { mode = \"Land\" }\n"
                         "lands-after-the-loss = { statustext = \"Landing detected\", after_fault = \"gps-loss\" }\n";
  return file;
}

std::vector<json> json_lines(const std::string& out) {
  std::vector<json> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(json::parse(line));
  return lines;
}

/// junit.xml as python3-junitparser reads it: suites, their counts, cases, results.
const char* kJunitReader = R"(
import json, sys
from junitparser import JUnitXml
xml = JUnitXml.fromfile(sys.argv[1])
suites = []
for suite in xml:
    cases = []
    for case in suite:
        cases.append({"name": case.name, "classname": case.classname, "system_out": case.system_out,
                      "results": [{"kind": type(r).__name__, "type": r.type, "message": r.message} for r in case.result]})
    suites.append({"name": suite.name, "tests": suite.tests, "failures": suite.failures, "errors": suite.errors, "cases": cases})
print(json.dumps(suites))
)";

TEST(CampaignE2E, ASmallCampaignWritesItsResultsAndJunitAsAConsumerReadsIt) {
  const auto dir = test::temp_dir();
  // A planted criterion no flight meets: each flight fails it, with the figure and its limit.
  const auto file = write_campaign(dir, 3, "planted = { figure = \"sim_time_s\", max = 1 }\n", 120, "report = true\n");
  const std::string out = dir + "/out";
  auto r = test::run_hitl({"--json", "campaign", "run", file, "-j", "2", "--out", out, "--history", dir + "/h.sqlite", "--label",
                           "first"},
                          std::chrono::seconds(120));
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;  // the planted criterion fails every flight
  const auto summary = test::last_json_line(r.out);
  EXPECT_EQ(summary["type"], "summary");
  EXPECT_EQ(summary["flights"], 4);
  EXPECT_EQ(summary["failed"], 4);
  EXPECT_EQ(summary["errors"], 0);
  EXPECT_EQ(summary, read_json(out + "/summary.json"));
  std::map<std::string, json> by_name;
  for (const auto& f : summary["results"]) {
    by_name[f["name"]] = f;
    // Only the planted criterion is broken: flown, disarmed hold.
    ASSERT_EQ(f["failures"].size(), 1u) << f.dump();
    EXPECT_EQ(f["failures"][0]["criterion"], "planted");
    const std::string folder = out + "/" + f["folder"].get<std::string>();
    for (const char* name : {"summary.json", "result.json", "flight.tlog", "log.txt", "report.html"})
      EXPECT_TRUE(std::filesystem::exists(folder + "/" + name)) << folder << "/" << name;
    const auto figures = read_json(folder + "/summary.json");
    EXPECT_EQ(figures["end"], "trajectory_done");
    EXPECT_EQ(figures["flight"]["id"], f["id"]);
    EXPECT_EQ(figures["stack"]["armed"], false);
    EXPECT_TRUE(figures["ekf_test_ratios"]["velocity"].is_number()) << figures["ekf_test_ratios"].dump();
    // The expectations held: the board's Land mode; its "Landing detected" after the GPS loss (those flights only).
    const auto result = read_json(folder + "/result.json");
    std::set<std::string> judged;
    for (const auto& v : result["criteria"]) {
      judged.insert(v["criterion"].get<std::string>());
      if (v["criterion"] != "planted") {
        EXPECT_TRUE(v["ok"].get<bool>()) << v.dump();
      }
    }
    EXPECT_EQ(judged.count("lands"), 1u);
    EXPECT_EQ(judged.count("lands-after-the-loss"), f["fault_case"] == "gps-loss" ? 1u : 0u) << f.dump();
    EXPECT_GT(figures["trajectory"]["samples"].get<int>(), 0);
  }
  ASSERT_EQ(by_name.size(), 4u);
  EXPECT_EQ(by_name.count("hover/gps-loss/seed-2"), 1u);
  // Status lines: each flight started and finished once.
  int started = 0, finished = 0;
  for (const auto& line : json_lines(r.out)) {
    if (line["type"] != "status") continue;
    if (line["event"] == "started") ++started;
    if (line["event"] == "finished") ++finished;
  }
  EXPECT_EQ(started, 4);
  EXPECT_EQ(finished, 4);
  // The run is in the history, each criterion with its figure over the 4 flights.
  auto history = test::run_hitl({"--json", "campaign", "history", "--history", dir + "/h.sqlite"});
  ASSERT_EQ(history.exit_code, 0) << history.out << history.err;
  const auto h = test::last_json_line(history.out);
  EXPECT_EQ(h["campaign"], "e2e");
  EXPECT_EQ(h["runs"], 1);
  ASSERT_EQ(h["trends"].size(), 5u) << h.dump();  // flown, disarmed, planted, lands, lands-after-the-loss
  const auto& planted = h["trends"][2];
  EXPECT_EQ(planted["criterion"], "planted");
  ASSERT_EQ(planted["points"].size(), 1u);
  EXPECT_EQ(planted["points"][0]["label"], "first");
  EXPECT_EQ(planted["points"][0]["failed"], 4);
  EXPECT_EQ(planted["points"][0]["flights"], 4);

  // The JUnit XML through python3-junitparser.
  if (!std::filesystem::exists("/usr/lib/python3/dist-packages/junitparser"))
    GTEST_SKIP() << "python3-junitparser is not installed (scripts/install-deps.sh --test installs it)";
  std::ofstream(dir + "/read_junit.py") << kJunitReader;
  test::Process reader({"/usr/bin/python3", dir + "/read_junit.py", out + "/junit.xml"});
  ASSERT_EQ(reader.wait(std::chrono::seconds(30)), 0) << reader.err();
  const auto suites = json::parse(reader.out());
  std::map<std::string, int> expected_suites{{"trajectory=hover", 4}, {"faults=none", 2}, {"faults=gps-loss", 2},
                                             {"seed=1", 2}, {"seed=2", 2}};
  ASSERT_EQ(suites.size(), expected_suites.size()) << suites.dump();
  for (const auto& s : suites) {
    ASSERT_EQ(expected_suites.count(s["name"]), 1u) << s["name"];
    EXPECT_EQ(s["tests"], expected_suites[s["name"]]);
    EXPECT_EQ(s["failures"], expected_suites[s["name"]]);
    EXPECT_EQ(s["errors"], 0);
    ASSERT_EQ(s["cases"].size(), static_cast<std::size_t>(expected_suites[s["name"]]));
    for (const auto& c : s["cases"]) {
      ASSERT_EQ(by_name.count(c["name"]), 1u) << c["name"];
      EXPECT_EQ(c["classname"], "e2e." + s["name"].get<std::string>());
      EXPECT_EQ(c["system_out"], by_name[c["name"]]["summary_line"]);
      ASSERT_EQ(c["results"].size(), 1u) << c.dump();
      EXPECT_EQ(c["results"][0]["kind"], "Failure");
      EXPECT_EQ(c["results"][0]["type"], "planted");
      const std::string message = c["results"][0]["message"];
      EXPECT_EQ(message.rfind("planted: sim_time_s = ", 0), 0u) << message;
      EXPECT_NE(message.find(", limit <= 1"), std::string::npos) << message;
    }
  }

  // Determinism in lockstep: the same flight alone (in-process, --only) gives the same figures.
  const auto& inside = by_name["hover/gps-loss/seed-2"];
  auto alone = test::run_hitl({"--json", "campaign", "run", file, "--only", std::to_string(inside["index"].get<int>()), "--out",
                               dir + "/alone"});
  ASSERT_EQ(alone.exit_code, 1) << alone.out << alone.err;
  const auto a = read_json(dir + "/alone/flights/" + inside["id"].get<std::string>() + "/summary.json");
  const auto b = read_json(out + "/" + inside["folder"].get<std::string>() + "/summary.json");
  for (const char* path : {"/trajectory/rms_m", "/trajectory/max_m", "/trajectory/samples", "/sim_time_s", "/steps",
                           "/landing/touchdowns", "/landing/max_rebound_m", "/landing/peak_accel_m_s2", "/position_ned_m"})
    EXPECT_EQ(a.at(json::json_pointer(path)), b.at(json::json_pointer(path))) << path;
}

TEST(CampaignE2E, AKilledFlightFailsAloneWithTheReasonAndRerunFailedFliesItAgain) {
  const auto dir = test::temp_dir();
  const auto file = write_campaign(dir, 30, "");  // long enough (~1.5 s) to be killed while it flies
  const std::string out = dir + "/out";
  test::Process run({test::hitl_binary(), "--json", "campaign", "run", file, "-j", "2", "--out", out});
  ASSERT_TRUE(run.wait_for_stdout("\"event\":\"started\"", std::chrono::seconds(30))) << run.out() << run.err();
  const auto first = json::parse(run.out_lines().front().find("started") != std::string::npos ? run.out_lines().front()
                                                                                                 : run.out_lines().at(1));
  ASSERT_EQ(first["event"], "started") << first.dump();
  ASSERT_EQ(::kill(first["pid"].get<int>(), SIGKILL), 0);
  EXPECT_EQ(run.wait(std::chrono::seconds(120)), 1) << run.err();
  const auto summary = read_json(out + "/summary.json");
  EXPECT_EQ(summary["passed"], 3) << summary.dump(2);
  EXPECT_EQ(summary["errors"], 1);
  for (const auto& f : summary["results"]) {
    if (f["index"] != first["index"]) {
      EXPECT_EQ(f["outcome"], "passed") << f.dump();
      continue;
    }
    EXPECT_EQ(f["outcome"], "error");
    const std::string reason = f["reason"];
    EXPECT_EQ(reason.rfind("killed by signal 9 (SIGKILL) without a result", 0), 0u) << reason;
    const auto log = read_text(out + "/" + f["folder"].get<std::string>() + "/log.txt");
    EXPECT_NE(log.find("hitl campaign: killed by signal 9 (SIGKILL) without a result"), std::string::npos) << log;
  }
  // --resume: nothing is missing, nothing flies; --rerun-failed flies the killed one only.
  auto resumed = test::run_hitl({"--json", "campaign", "run", file, "--out", out, "--resume"});
  EXPECT_EQ(resumed.exit_code, 1) << resumed.err;
  EXPECT_EQ(resumed.out.find("\"event\":\"started\""), std::string::npos) << resumed.out;
  auto rerun = test::run_hitl({"--json", "campaign", "run", file, "--out", out, "--rerun-failed"}, std::chrono::seconds(60));
  EXPECT_EQ(rerun.exit_code, 0) << rerun.out << rerun.err;
  std::set<int> flown;
  for (const auto& line : json_lines(rerun.out))
    if (line["type"] == "status" && line["event"] == "started") flown.insert(line["index"].get<int>());
  EXPECT_EQ(flown, std::set<int>{first["index"].get<int>()});
  EXPECT_EQ(test::last_json_line(rerun.out)["passed"], 4);
}

TEST(CampaignE2E, CtrlCStopsEveryFlightAndResumeFliesOnlyWhatIsMissing) {
  const auto dir = test::temp_dir();
  const auto file = write_campaign(dir, 30, "");
  const std::string out = dir + "/out";
  test::Process run({test::hitl_binary(), "--json", "campaign", "run", file, "-j", "1", "--out", out});
  ASSERT_TRUE(run.wait_for_stdout("\"event\":\"finished\"", std::chrono::seconds(60))) << run.out() << run.err();
  run.signal(SIGINT);
  EXPECT_EQ(run.wait(std::chrono::seconds(30)), 1) << run.err();
  const auto stopped = read_json(out + "/summary.json");
  EXPECT_TRUE(stopped["stopped"].get<bool>());
  const int missing = stopped["missing"];
  EXPECT_GE(missing, 1);
  EXPECT_EQ(stopped["passed"].get<int>() + missing, 4) << stopped.dump(2);
  // A fresh run into the same folder is refused: it would overwrite.
  auto fresh = test::run_hitl({"campaign", "run", file, "--out", out});
  EXPECT_EQ(fresh.exit_code, 2);
  EXPECT_NE(fresh.err.find("--resume"), std::string::npos) << fresh.err;
  auto resumed = test::run_hitl({"--json", "campaign", "run", file, "-j", "2", "--out", out, "--resume"}, std::chrono::seconds(60));
  EXPECT_EQ(resumed.exit_code, 0) << resumed.out << resumed.err;
  int started = 0;
  for (const auto& line : json_lines(resumed.out))
    if (line["type"] == "status" && line["event"] == "started") ++started;
  EXPECT_EQ(started, missing);
  EXPECT_EQ(test::last_json_line(resumed.out)["passed"], 4);
}

TEST(CampaignE2E, AFlightPastItsTimeLimitIsKilledAndSaysSo) {
  const auto dir = test::temp_dir();
  const auto file = write_campaign(dir, 30, "", 0.2);
  auto r = test::run_hitl({"--json", "campaign", "run", file, "-j", "2", "--out", dir + "/out"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto summary = test::last_json_line(r.out);
  EXPECT_EQ(summary["errors"], 4);
  const std::string reason = summary["results"][0]["reason"];
  EXPECT_EQ(reason.rfind("no result within the time limit of 0.2 s (campaign.time_limit_s): killed", 0), 0u) << reason;
}

// Past one machine: each flight run on its own (`--only INDEX`, as a Slurm task, a Kubernetes pod
// or a CI job runs it) into one folder, then `collect` writes the folder's summary and JUnit and
// adds one run to the history; a flight not run counts as not flown. `matrix` and `k8s` describe
// the same flights.
TEST(CampaignE2E, FlightsRunElsewhereAreCollectedAndDescribedForOtherEngines) {
  const std::string dir = test::temp_dir();
  const std::string file = write_campaign(dir, 3, "");
  const std::string out = dir + "/shared";
  test::Process a({test::hitl_binary(), "campaign", "run", file, "--only", "0", "--out", out});
  test::Process b({test::hitl_binary(), "campaign", "run", file, "--only", "3", "--out", out});
  EXPECT_EQ(a.wait(std::chrono::seconds(120)), 0) << a.err();
  EXPECT_EQ(b.wait(std::chrono::seconds(120)), 0) << b.err();
  auto c = test::run_hitl({"--json", "campaign", "collect", file, "--out", out, "--history", dir + "/h.sqlite", "--label", "k8s"});
  EXPECT_EQ(c.exit_code, 1) << c.err;  // two flights not flown
  const auto summary = test::last_json_line(c.out);
  EXPECT_EQ(summary["flights"], 4) << summary.dump();
  EXPECT_EQ(summary["passed"], 2) << summary.dump();
  EXPECT_EQ(summary["missing"], 2) << summary.dump();
  const auto file_summary = read_json(out + "/summary.json");
  std::map<std::string, int> outcomes;
  for (const auto& f : file_summary["results"]) ++outcomes[f["outcome"].get<std::string>()];
  EXPECT_EQ(outcomes["passed"], 2) << file_summary.dump();
  EXPECT_EQ(outcomes["missing"], 2) << file_summary.dump();
  EXPECT_TRUE(std::filesystem::exists(out + "/junit.xml"));
  auto h = test::run_hitl({"--json", "campaign", "history", "--history", dir + "/h.sqlite"});
  EXPECT_NE(h.out.find("\"label\":\"k8s\""), std::string::npos) << h.out << h.err;
  auto empty = test::run_hitl({"campaign", "collect", file, "--out", dir + "/nothing-here", "--no-history"});
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("has no flights/ folder"), std::string::npos) << empty.err;

  auto m = test::run_hitl({"campaign", "matrix", file});
  ASSERT_EQ(m.exit_code, 0) << m.err;
  const auto matrix = json::parse(m.out);
  ASSERT_EQ(matrix["include"].size(), 4u);
  EXPECT_EQ(matrix["include"][3]["index"], 3);
  auto k = test::run_hitl({"campaign", "k8s", file, "--image", "hitl:test", "-o", dir + "/job.json"});
  ASSERT_EQ(k.exit_code, 0) << k.err;
  const auto job = read_json(dir + "/job.json");
  EXPECT_EQ(job["spec"]["completions"], 4);
  EXPECT_EQ(job["spec"]["completionMode"], "Indexed");
  EXPECT_EQ(test::run_hitl({"campaign", "k8s", file}).exit_code, 2);  // --image is needed
}

TEST(CampaignE2E, ABadFileIsRefusedWithFileLineAndKey) {
  const auto dir = test::temp_dir();
  const auto file = write_campaign(dir, 3, "bad = { figure = \"trajectory.rms\", max = 1 }\n");
  auto r = test::run_hitl({"campaign", "run", file});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(file + ":12: criteria.bad.figure: \"trajectory.rms\" is not a figure"), std::string::npos) << r.err;
}

TEST(CampaignE2E, APx4CampaignWithABadPx4FolderIsRefusedBeforeAnyFlight) {
  // No PX4 needed: the folder is checked, as hitl sim --px4 checks it, before anything flies.
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/hover.json") << R"({"waypoints": [{"t": 0, "x": 0, "y": 0, "z": 2, "yaw": 0}]})";
  const std::string file = dir + "/px4.toml";
  std::ofstream(file) << "[campaign]\nname = \"p\"\nstack = \"px4\"\npx4 = \"no-px4-here\"\n"
                         "[matrix]\ntrajectories = [\"hover.json\"]\nspeeds = [5]\n";
  auto r = test::run_hitl({"campaign", "run", file, "--out", dir + "/out", "--no-history"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(file + ":4: campaign.px4: '" + dir + "/no-px4-here': no such folder"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << "nothing flew";
  // --px4 DIR stands in for the file's; its refusal names the option, in hitl sim --px4's words.
  r = test::run_hitl({"campaign", "run", file, "--px4", dir, "--out", dir + "/out", "--no-history"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--px4: '" + dir + "' is not a PX4 SITL build: no bin/px4"), std::string::npos) << r.err;
  const auto sim = test::run_hitl({"sim", "--px4", dir, "--duration", "1"});
  EXPECT_NE(sim.err.find("--px4: '" + dir + "' is not a PX4 SITL build: no bin/px4"), std::string::npos) << sim.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
}

}  // namespace
}  // namespace hitl
