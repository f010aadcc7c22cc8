// Campaigns against real PX4 SITL (ctest -L px4): HITL_PX4_DIR names a PX4 v1.16.0 SITL build or a
// PX4 tree with build/px4_sitl_default (scripts/px4-sitl.sh); without it every test here skips,
// saying so. A hover with and without a GPS loss at -j 2, each flight starting its own PX4 (two at
// once: they must not collide), both pass, PX4's mode change and console failsafe after the loss
// found by expectations; each flight's folder holds PX4's console and ULog; the history has PX4's
// version; no PX4 is left behind, neither after the flights nor after a Ctrl-C of the campaign nor
// after a flight killed at its time limit.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"
#include "tests/support/px4_dir.h"
#include "tests/support/tools.h"

namespace hitl::test {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;


/// How many processes have `text` in their command line (PX4's has its working folder: -w DIR).
int processes_naming(const std::string& text) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = read_text(entry.path().string() + "/cmdline");
    for (auto& c : cmdline)
      if (c == '\0') c = ' ';
    if (cmdline.find(text) != std::string::npos && process_running(std::stoi(pid))) ++n;
  }
  return n;
}

/// The ULogs under a flight's PX4 working folder (log/<date>/<time>.ulg).
std::size_t ulogs_in(const std::string& dir) {
  std::size_t n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec); !ec && it != std::filesystem::recursive_directory_iterator();
       it.increment(ec))
    if (it->path().extension() == ".ulg" && it->file_size() > 0) ++n;
  return n;
}

class Px4Campaign : public ::testing::Test {
 protected:
  void SetUp() override {
    px4_dir_ = px4_dir();
    if (px4_dir_.empty()) GTEST_SKIP() << kNoPx4Reason;
    dir_ = temp_dir();
    ::setenv("XDG_DATA_HOME", dir_.c_str(), 1);  // never the user's history
  }

  /// The 20 s hover against PX4 at 5x without a fault and with a GPS loss (2 flights), PX4's folder
  /// named in the file. Seed 1: with seeds 2 and 3 PX4's takeoff (as hitl sim --px4 --seed 2's)
  /// ended 0.6-1.1 m short of its height, so the pilot never left TAKEOFF.
  std::string write_campaign(double time_limit_s = 120) const {
    const std::string file = dir_ + "/px4.toml";
    std::ofstream(file) << "[campaign]\nname = \"px4-e2e\"\nstack = \"px4\"\npx4 = \"" << px4_dir_
                        << "\"\npx4_params = { SYS_FAILURE_EN = 1 }\ntime_limit_s = " << time_limit_s
                        << "\n[matrix]\ntrajectories = [\"" << HITL_SOURCE_DIR << "/docs/examples/hover.json\"]\nspeeds = [5]\n"
                           "[faults]\nnone = []\ngps-loss = [\"gps-loss@15+10\"]\n"
                           "[criteria]\ntracking = { figure = \"trajectory.rms_m\", max = 1.5 }\n"
                           "disarmed = { figure = \"stack.armed\", equals = false }\n"
                           "landed = { figure = \"stack.landed_state\", equals = \"on_ground\" }\n"
                           "[expect]\ntakes-off = { mode = \"Takeoff\" }\nlands = { mode = \"Land\" }\narms = { event = \"^armed$\" }\n"
                           "altitude-mode = { mode = \"Altitude\", after_fault = \"gps-loss\", within_s = 10 }\n"
                           "failsafe = { event = \"Failsafe activated\", after_fault = \"gps-loss\", within_s = 10 }\n";
    return file;
  }

  std::string px4_dir_;
  std::string dir_;
};

TEST_F(Px4Campaign, TwoFlightsAtOnceEachWithItsOwnPx4BothPass) {
  const std::string file = write_campaign();
  const std::string out = dir_ + "/out", history = dir_ + "/h.sqlite";
  const auto started = std::chrono::steady_clock::now();
  const auto r = run_hitl({"-v", "campaign", "run", file, "-j", "2", "--out", out, "--history", history, "--label", "e2e"}, 300s);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.err.find("against PX4 v"), std::string::npos) << r.err;

  const auto summary = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(summary["stack"], "px4");
  const std::string version = summary["stack_version"].get<std::string>();
  EXPECT_EQ(version.rfind("v1.", 0), 0u) << summary.dump();
  ASSERT_EQ(summary["results"].size(), 2u);
  std::set<std::string> instances;
  for (const auto& f : summary["results"]) {
    EXPECT_EQ(f["outcome"], "passed") << f.dump();
    const std::string folder = out + "/" + f["folder"].get<std::string>();
    EXPECT_GT(std::filesystem::file_size(folder + "/flight.px4.log"), 0u) << "PX4's console in " << folder;
    EXPECT_GE(ulogs_in(folder + "/flight.px4/log"), 1u) << "PX4's ULog in " << folder;
    const auto figures = json::parse(read_text(folder + "/summary.json"));
    EXPECT_EQ(figures["stack"]["kind"], "px4");
    EXPECT_EQ(figures["stack"]["version"], version);
    EXPECT_EQ(figures["stack"]["landed_state"], "on_ground") << "from PX4's GCS instance";
    EXPECT_FALSE(figures["stack"]["mode"].get<std::string>().empty());
    if (f["name"].get<std::string>().find("gps-loss") != std::string::npos) {  // PX4's reaction, judged
      std::set<std::string> judged;
      const auto result = json::parse(read_text(folder + "/result.json"));
      for (const auto& v : result["criteria"])
        if (v["ok"] == true) judged.insert(v["criterion"].get<std::string>());
      EXPECT_EQ(judged.count("altitude-mode"), 1u) << read_text(folder + "/result.json");
      EXPECT_EQ(judged.count("failsafe"), 1u) << read_text(folder + "/result.json");
    }
    // Each flight's PX4 took an instance of its own (two at once: two instances).
    std::smatch m;
    const std::string log = read_text(folder + "/log.txt");
    if (std::regex_search(log, m, std::regex("started PX4 [^ ]* as instance ([0-9]+)"))) instances.insert(m[1]);
    std::printf("[ figures  ] %s: tracking RMS %.3f m, max %.3f m; %.1f s simulated in %.2f s; flight %.1f s in its process\n",
                f["name"].get<std::string>().c_str(), figures["trajectory"]["rms_m"].get<double>(),
                figures["trajectory"]["max_m"].get<double>(), figures["sim_time_s"].get<double>(),
                figures["wall_time_s"].get<double>(), f["wall_s"].get<double>());
  }
  EXPECT_EQ(instances.size(), 2u) << "two PX4s at once, each on its own instance";
  std::printf("[ figures  ] 2 PX4 flights at -j 2 in %.1f s\n", wall_s);
  EXPECT_NE(read_text(out + "/junit.xml").find("<property name=\"stack\" value=\"px4\""), std::string::npos);

  // The history's run names PX4's version.
  const auto h = run_hitl({"--json", "campaign", "history", "--history", history});
  ASSERT_EQ(h.exit_code, 0) << h.err;
  const auto trends = last_json_line(h.out)["trends"];
  ASSERT_FALSE(trends.empty()) << h.out;
  EXPECT_EQ(trends[0]["points"][0]["stack_version"], version) << h.out;
  EXPECT_EQ(trends[0]["points"][0]["label"], "e2e");

  EXPECT_EQ(processes_naming(out), 0) << "a PX4 left running in " << out;

  // hitl report finds the ULog beside the flight's recording, as beside a hitl sim --px4 recording.
  const std::string tlog = out + "/" + summary["results"][0]["folder"].get<std::string>() + "/flight.tlog";
  const auto report = run_hitl({"--json", "report", tlog, "-o", dir_ + "/report.html"}, 120s);
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const auto written = last_json_line(report.out);
  EXPECT_FALSE(written["ulog"].is_null()) << written.dump();
}

TEST_F(Px4Campaign, CtrlCOfTheCampaignLeavesNoPx4) {
  const std::string file = write_campaign();
  const std::string out = dir_ + "/stopped";
  Process campaign({hitl_binary(), "campaign", "run", file, "-j", "2", "--out", out, "--no-history"});
  // Both flights' PX4s running (each names its working folder in the results folder).
  const auto until = std::chrono::steady_clock::now() + 60s;
  while (processes_naming(out + "/flights/") < 2 && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(100ms);
  ASSERT_GE(processes_naming(out + "/flights/"), 2) << campaign.err();
  std::this_thread::sleep_for(2s);  // in flight
  campaign.signal(SIGINT);
  EXPECT_EQ(campaign.wait(60s), 1) << campaign.err();
  EXPECT_EQ(processes_naming(out + "/flights/"), 0) << "a PX4 left running after Ctrl-C";
  const auto summary = json::parse(read_text(out + "/summary.json"));
  EXPECT_EQ(summary["stopped"], true);
}

TEST_F(Px4Campaign, AFlightKilledAtItsTimeLimitTakesItsPx4Along) {
  // The runner kills a flight past its limit with SIGKILL to the flight's process group: PX4 (in a
  // group of its own) must die with it, not live on as an orphan.
  const std::string file = write_campaign(4);
  const std::string out = dir_ + "/limited";
  const auto r = run_hitl({"campaign", "run", file, "-j", "2", "--out", out, "--no-history"}, 120s);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no result within the time limit of 4 s"), std::string::npos) << r.err;
  const auto until = std::chrono::steady_clock::now() + 10s;
  while (processes_naming(out + "/flights/") > 0 && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(100ms);
  EXPECT_EQ(processes_naming(out + "/flights/"), 0) << "a PX4 left running after its flight was killed";
}

}  // namespace
}  // namespace hitl::test
