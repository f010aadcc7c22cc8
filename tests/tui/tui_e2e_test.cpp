// `hitl sim --tui` end to end: the emulated board (`hitl target --lockstep`) and the simulator with
// its dashboard inside a detached tmux session of fixed size (120x40); keys go in with send-keys,
// the screen comes back with capture-pane. Arm, take off, and see the armed state, the rates and
// the altitude rising; q quits and the terminal shows the summary. `f` flies the -t file in-process.
#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/process.h"
#include "tests/support/tmux.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

using test::shell_quoted;
using test::Tmux;
using test::tmux_path;

std::optional<double> number_after(const std::string& screen, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(screen, m, std::regex(pattern))) return std::nullopt;
  return std::stod(m[1].str());
}

/// `hitl target` on loopback in lockstep, and the `hitl sim --tui` command line a tmux pane runs
/// against it (`options` between the ports and --tui); the pane stays open after hitl ends.
struct SimAgainstTarget {
  uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), clients = test::free_udp_port(),
           local = test::free_udp_port();
  test::Process board{{test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil),
                       "--gcs-port", std::to_string(gcs), "--vio-port", "0", "--lockstep"}};

  std::string sim_command(const std::string& options) const {
    return shell_quoted(test::hitl_binary()) + " sim -i 127.0.0.1 --hil-port " + std::to_string(hil) + " --local-port " +
           std::to_string(local) + " --no-vio --clients " + std::to_string(clients) + " " + options +
           " --tui; echo HITL_EXIT=$?; sleep 60";
  }
};

TEST(TuiE2E, ArmTakeOffAndWatchTheDashboard) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  SimAgainstTarget setup;
  ASSERT_TRUE(setup.board.wait_for_stderr("EMULATED", 10s)) << setup.board.err();

  Tmux tmux(tmux_bin, "tui-sim");
  tmux.start(setup.sim_command("--lockstep --speed 1"));

  std::string s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("Data paths") != std::string::npos; }, 20s, &s)) << s;
  EXPECT_NE(s.find("hitl sim"), std::string::npos);
  for (const char* panel : {"dsp_hitl", "EKF", "Vehicle", "Messages", "Link"}) EXPECT_NE(s.find(panel), std::string::npos) << panel;

  // The rates: the IMU path (HIL_SENSOR) measured against its 250 Hz, and the board's dsp_hitl
  // counters polled through the shell.
  ASSERT_TRUE(tmux.until(
      [](const std::string& x) {
        const auto imu = number_after(x, R"(IMU\s+250\.0\s+([0-9.]+))");
        const auto dsp = number_after(x, R"(HIL sensor_imu received\s+[0-9]+\s+([0-9.]+))");
        return imu && *imu > 125.0 && dsp && *dsp > 125.0;
      },
      60s, &s))
      << s;

  // The estimator converges (SYS_STATUS says ready), then arm: a denial is retried.
  ASSERT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(%\s+ready)")); }, 90s, &s)) << s;
  bool armed = false;
  for (int attempt = 0; attempt < 5 && !armed; ++attempt) {
    tmux.keys({"a"});
    armed = tmux.until([](const std::string& x) { return x.find("ARMED") != std::string::npos; }, 15s, &s);
  }
  ASSERT_TRUE(armed) << s;
  EXPECT_NE(s.find("armed"), std::string::npos) << s;  // the command's outcome in the messages panel

  // Take off: the estimate's altitude and the truth's rise.
  const double before_m = number_after(s, R"(alt (-?[0-9.]+) m est)").value_or(0.0);
  tmux.keys({"t"});
  ASSERT_TRUE(tmux.until(
      [&](const std::string& x) {
        const auto est = number_after(x, R"(alt (-?[0-9.]+) m est)");
        const auto truth = number_after(x, R"(, (-?[0-9.]+) m truth)");
        return est && truth && *est > before_m + 1.0 && *truth > 1.0;
      },
      60s, &s))
      << s;
  EXPECT_NE(s.find("takeoff accepted"), std::string::npos) << s;
  EXPECT_TRUE(s.find("taking off") != std::string::npos || s.find("in air") != std::string::npos) << s;

  // q: the dashboard closes, the terminal is given back and the summary printed.
  tmux.keys({"q"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 30s, &s)) << s;
  EXPECT_NE(s.find("HITL_EXIT=0"), std::string::npos) << s;
  EXPECT_NE(s.find("real-time factor"), std::string::npos) << s;  // print_summary's first line
  EXPECT_EQ(s.find("Data paths"), std::string::npos) << s;         // the dashboard is gone
  setup.board.signal(SIGINT);
  setup.board.wait(10s);
}

/// How many braille cells (U+2800..U+28FF, UTF-8 E2 A0..A3 xx) `screen` holds.
int braille_cells(const std::string& screen) {
  int n = 0;
  for (std::size_t i = 0; i + 2 < screen.size(); ++i)
    if (static_cast<unsigned char>(screen[i]) == 0xE2 && (static_cast<unsigned char>(screen[i + 1]) & 0xFC) == 0xA0) ++n;
  return n;
}

// With room to spare the dashboard draws its graphs (the last 60 s): braille in a UTF-8 locale,
// ASCII with HITL_GRAPH_SYMBOL=ascii; at 80x24 there are none.
TEST(TuiE2E, GraphsAt200x60InBrailleAndAscii) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  SimAgainstTarget setup;
  std::string s;
  {
    Tmux tmux(tmux_bin, "tui-graphs");
    tmux.start("LC_ALL=C.UTF-8 " + setup.sim_command("--lockstep --speed 1"), 200, 60);
    ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("Graphs, last 60 s") != std::string::npos; }, 20s, &s)) << s;
    // The rates' graphs fill in from the right within a few frames.
    EXPECT_TRUE(tmux.until([](const std::string& x) { return braille_cells(x) >= 10; }, 20s, &s)) << s;
    EXPECT_NE(s.find("Altitude m: truth"), std::string::npos) << s;
    EXPECT_TRUE(std::regex_search(s, std::regex(R"(IMU +\S+ +[0-9.]+/250\.0 Hz)"))) << s;
    tmux.keys({"q"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 30s, &s)) << s;
    EXPECT_NE(s.find("HITL_EXIT=0"), std::string::npos) << s;
  }
  {
    Tmux tmux(tmux_bin, "tui-graphs-ascii");
    tmux.start("LC_ALL=C.UTF-8 HITL_GRAPH_SYMBOL=ascii " + setup.sim_command("--lockstep --speed 1"), 200, 60);
    ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("Graphs, last 60 s") != std::string::npos; }, 20s, &s)) << s;
    EXPECT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(IMU +[-_']+ +[0-9.]+/250\.0 Hz)")); }, 20s, &s)) << s;
    EXPECT_EQ(braille_cells(s), 0) << s;
    tmux.keys({"q"});
    ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 30s, &s)) << s;
  }
  setup.board.signal(SIGINT);
  setup.board.wait(10s);
}

// While `f` flies the trajectory, the graphs add the tracking error the flight is scored on.
TEST(TuiE2E, GraphsShowTheTrackingErrorWhileATrajectoryFlies) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  SimAgainstTarget setup;
  const std::string trajectory = std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json";
  Tmux tmux(tmux_bin, "tui-graphs-fly");
  tmux.start("LC_ALL=C.UTF-8 " + setup.sim_command("--lockstep --speed 5 -t " + shell_quoted(trajectory)), 200, 60);
  std::string s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(%\s+ready)")); }, 90s, &s)) << s;
  EXPECT_EQ(s.find("Tracking error m"), std::string::npos) << s;  // nothing flown yet
  tmux.keys({"f"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(Tracking error m: now \d+\.\d\d)")); }, 90s, &s)) << s;
  EXPECT_GT(braille_cells(s), 10) << s;
  tmux.keys({"q"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 30s, &s)) << s;
  setup.board.signal(SIGINT);
  setup.board.wait(10s);
}

/// The processes `pid` started (its threads' children), from /proc.
std::vector<std::string> children_of(const std::string& pid) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + pid + "/task", ec)) {
    std::ifstream in(task.path() / "children");
    for (std::string child; in >> child;) out.push_back(child);
  }
  return out;
}

// `hitl sim --tui -t FILE`: the trajectory waits for `f`, which flies it in-process (the same flight
// as `hitl fly trajectory`, no child process) through the session's client port: the pilot's states
// in the messages panel, the vehicle armed and in the air, and the flight's end pinned in the header.
TEST(TuiE2E, FKeyFliesTheTrajectoryInProcess) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  SimAgainstTarget setup;
  ASSERT_TRUE(setup.board.wait_for_stderr("EMULATED", 10s)) << setup.board.err();

  Tmux tmux(tmux_bin, "tui-fly");
  const std::string trajectory = std::string(HITL_SOURCE_DIR) + "/docs/examples/square.json";
  tmux.start(setup.sim_command("--lockstep --speed 5 -t " + shell_quoted(trajectory)));
  std::string s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("Data paths") != std::string::npos; }, 20s, &s)) << s;
  EXPECT_EQ(s.find("ARMED"), std::string::npos) << s;  // -t with --tui waits for the key
  ASSERT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(%\s+ready)")); }, 90s, &s)) << s;

  tmux.keys({"f"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("f: flying") != std::string::npos; }, 10s, &s)) << s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("trajectory: TRAJECTORY") != std::string::npos; }, 90s, &s)) << s;
  // In-process: the shell in the pane started hitl sim, and hitl sim started nothing.
  const std::string shell_pid = tmux.run({"display-message", "-p", "-t", "t", "#{pane_pid}"});
  const auto sims = children_of(shell_pid.substr(0, shell_pid.find_first_of("\r\n")));
  ASSERT_EQ(sims.size(), 1u) << shell_pid;
  EXPECT_TRUE(children_of(sims[0]).empty()) << "hitl sim runs a child process while flying";

  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("trajectory ended: done") != std::string::npos; }, 150s, &s))
      << s;
  EXPECT_NE(s.find("DONE; velocity mode; tracking error"), std::string::npos) << s;

  tmux.keys({"q"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 30s, &s)) << s;
  EXPECT_NE(s.find("HITL_EXIT=0"), std::string::npos) << s;
  setup.board.signal(SIGINT);
  setup.board.wait(10s);
}

/// The pane's whole text, wrapped lines joined and its history included (a JSON line is long).
std::string whole_pane(Tmux& tmux) { return tmux.run({"capture-pane", "-p", "-J", "-S", "-", "-t", "t"}); }

// `x` opens the fault menu, at 80x24: pick gps-loss by typing its name, start it for 30 s from its
// line, see it on the state line, in the messages and in the menu's active faults, clear it from
// the menu; bad arguments are refused in the menu with the catalogue's message; the summary's
// `faults` and the recording's STATUSTEXT have the start and the end.
TEST(TuiE2E, XKeyMenuStartsAndClearsAFaultLive) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  SimAgainstTarget setup;
  ASSERT_TRUE(setup.board.wait_for_stderr("EMULATED", 10s)) << setup.board.err();
  const std::string tlog = ::testing::TempDir() + "tui_fault_menu_" + std::to_string(::getpid()) + ".tlog";
  Tmux tmux(tmux_bin, "tui-fault");
  tmux.start(setup.sim_command("--lockstep --json --record " + shell_quoted(tlog)), 80, 24);
  std::string s;
  auto shows = [&](const std::string& text, std::chrono::seconds timeout = 10s) {
    return tmux.until([&](const std::string& x) { return x.find(text) != std::string::npos; }, timeout, &s);
  };
  ASSERT_TRUE(shows("Data paths", 20s)) << s;
  tmux.keys({"x"});
  ASSERT_TRUE(shows("Faults: start or clear")) << s;
  EXPECT_NE(s.find("Vehicle"), std::string::npos) << s;
  EXPECT_EQ(s.find("Active faults"), std::string::npos) << s;  // none yet
  tmux.keys({"gps-loss"});
  ASSERT_TRUE(shows("filter: gps-loss_")) << s;
  EXPECT_NE(s.find("no HIL_GPS is sent"), std::string::npos) << s;
  tmux.keys({"Enter"});
  ASSERT_TRUE(shows("> gps-loss_")) << s;
  EXPECT_NE(s.find("Start gps-loss (GPS)"), std::string::npos) << s;
  tmux.keys({"+30", "Enter"});
  // On the state line with what is left of it, and its start in the messages (wrapped at 80 columns).
  ASSERT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(faults: gps-loss \(\d+ s left\))")); }, 10s, &s))
      << s;
  ASSERT_TRUE(shows("started (30 s)")) << s;
  EXPECT_EQ(s.find("Faults: start or clear"), std::string::npos) << s;  // closed

  // Refused in the menu: the catalogue's message, nothing started, the menu open.
  tmux.keys({"x"});
  ASSERT_TRUE(shows("Active faults (1)")) << s;
  EXPECT_TRUE(std::regex_search(s, std::regex(R"(gps-loss +since [0-9.]+ s, [0-9.]+ s left)"))) << s;
  tmux.keys({"motor"});
  ASSERT_TRUE(shows("filter: motor_")) << s;
  tmux.keys({"Enter"});
  ASSERT_TRUE(shows("> motor:2,0.75_")) << s;
  tmux.keys({"BSpace", "BSpace", "BSpace", "BSpace", "9", "Enter"});
  ASSERT_TRUE(shows("k must be within 0..2 (got 9)")) << s;
  EXPECT_NE(s.find("Faults: start one now"), std::string::npos) << s;
  EXPECT_EQ(s.substr(0, s.find('\n')).find("motor"), std::string::npos) << s;  // not on the state line
  tmux.keys({"Escape"});
  ASSERT_TRUE(shows("filter: motor_")) << s;
  tmux.keys({"BSpace", "BSpace", "BSpace", "BSpace", "BSpace"});
  ASSERT_TRUE(shows("type to filter")) << s;

  // Enter on the active fault clears it.
  tmux.keys({"Home", "Enter"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("faults: gps-loss") == std::string::npos; }, 10s, &s)) << s;
  ASSERT_TRUE(shows("ended")) << s;

  tmux.keys({"q"});
  ASSERT_TRUE(shows("HITL_EXIT=", 30s)) << s;
  const std::string pane = whole_pane(tmux);
  EXPECT_NE(pane.find("HITL_EXIT=0"), std::string::npos) << pane;
  // The summary (--json): one gps-loss with its start and end, and nothing else started.
  std::optional<nlohmann::json> summary;
  std::istringstream lines(pane);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("{", 0) == 0 && line.find("\"faults\"") != std::string::npos) summary = nlohmann::json::parse(line, nullptr, false);
  ASSERT_TRUE(summary && !summary->is_discarded()) << pane;
  const auto& faults = (*summary)["faults"];
  ASSERT_EQ(faults.size(), 1u) << faults.dump();
  EXPECT_EQ(faults[0]["name"], "gps-loss");
  ASSERT_TRUE(faults[0]["end_s"].is_number()) << faults.dump();
  EXPECT_LT(faults[0]["end_s"].get<double>() - faults[0]["start_s"].get<double>(), 30.0);  // cleared before its 30 s
  // The recording has the simulator's STATUSTEXT for both.
  std::ifstream in(tlog, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("fault gps-loss started (30 s)"), std::string::npos);
  EXPECT_NE(bytes.find("fault gps-loss ended"), std::string::npos);
  std::remove(tlog.c_str());
  setup.board.signal(SIGINT);
  setup.board.wait(10s);
}

// `hitl bridge --tui`: the link panel shows the board up with a TIMESYNC round trip, the data
// paths show packets each way, and `a` goes through the bridge's client port to the board, whose
// refusal (no simulator feeds its EKF) comes back in the messages panel.
TEST(TuiE2E, BridgeDashboardShowsTheLinkAndActsThroughItsClientPort) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  const uint16_t hil = test::free_udp_port(), gcs = test::free_udp_port(), clients = test::free_udp_port(),
                 local = test::free_udp_port();
  test::Process board({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(hil), "--gcs-port",
                       std::to_string(gcs), "--vio-port", "0"});
  ASSERT_TRUE(board.wait_for_stderr("EMULATED", 10s)) << board.err();

  Tmux tmux(tmux_bin, "tui-bridge");
  const std::string bridge = shell_quoted(test::hitl_binary()) + " bridge -i 127.0.0.1 --port " + std::to_string(gcs) +
                             " --local-port " + std::to_string(local) + " --clients " + std::to_string(clients) +
                             " --tui; echo HITL_EXIT=$?; sleep 60";
  tmux.start(bridge);

  std::string s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("board up") != std::string::npos; }, 20s, &s)) << s;
  EXPECT_NE(s.find("hitl bridge"), std::string::npos) << s;
  EXPECT_NE(s.find("Link board 127.0.0.1:" + std::to_string(gcs)), std::string::npos) << s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return std::regex_search(x, std::regex(R"(rtt \d+\.\d+ ms)")); }, 15s, &s)) << s;
  // Packets from the board measured as a rate (HEARTBEAT and the streams: well above 1 per second).
  ASSERT_TRUE(tmux.until(
      [](const std::string& x) {
        auto rate = number_after(x, R"(rx board\s+-\s+([0-9.]+))");
        return rate && *rate >= 2.0;
      },
      15s, &s))
      << s;
  // The vehicle panel fills from the board through the bridge's client port.
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("on ground") != std::string::npos; }, 20s, &s)) << s;
  // The footer lists only the keys that work on a bridge (issue 18).
  const std::string footer = s.substr(s.rfind("a:arm"));
  EXPECT_EQ(footer.find("p:pause"), std::string::npos) << footer;
  EXPECT_EQ(footer.find("f:fly"), std::string::npos) << footer;
  EXPECT_NE(footer.find("s:shell"), std::string::npos) << footer;
  // The last key's outcome is pinned in the header (its first line).
  auto header = [](const std::string& x) { return x.substr(0, x.find('\n')); };
  tmux.keys({"a"});
  ASSERT_TRUE(tmux.until([&](const std::string& x) { return header(x).find("arm denied") != std::string::npos; }, 20s, &s)) << s;
  tmux.keys({"p"});  // no simulator to pause: refused with the reason
  ASSERT_TRUE(tmux.until([&](const std::string& x) { return header(x).find("pause/resume: hitl bridge runs no") != std::string::npos; }, 10s, &s)) << s;
  // The messages scroll: a page back shows where it is, End returns to the newest.
  for (int i = 0; i < 2; ++i) {  // two commands' output: more than the panel holds
    tmux.keys({"s"});
    tmux.keys({"help", "Enter"});
  }
  ASSERT_TRUE(tmux.until([&](const std::string& x) { return header(x).find("shell> help: done") != std::string::npos; }, 15s, &s)) << s;
  std::this_thread::sleep_for(1s);  // the second one's output
  tmux.keys({"PPage"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find(", End: newest") != std::string::npos; }, 5s, &s)) << s;
  tmux.keys({"End"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find(", End: newest") == std::string::npos; }, 5s, &s)) << s;

  tmux.keys({"q"});
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 30s, &s)) << s;
  EXPECT_NE(s.find("HITL_EXIT=0"), std::string::npos) << s;
  board.signal(SIGINT);
  board.wait(10s);
}

// `hitl demo --tui` (README, scripts/demo.sh, the guide): the sim dashboard on the demo's flight,
// which arms and flies by itself; when the square is done the dashboard closes and the report follows.
TEST(TuiE2E, DemoDashboardFliesTheSquareThenReports) {
  const std::string tmux_bin = tmux_path();
  if (tmux_bin.empty()) GTEST_SKIP() << "tmux is not installed (scripts/install-deps.sh --test installs it)";
  Tmux tmux(tmux_bin, "tui-demo");
  const std::string demo = shell_quoted(test::hitl_binary()) + " demo --tui --speed 4; echo HITL_EXIT=$?; sleep 60";
  tmux.start(demo);
  std::string s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("Data paths") != std::string::npos; }, 20s, &s)) << s;
  EXPECT_NE(s.find("hitl demo"), std::string::npos) << s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("ARMED") != std::string::npos; }, 120s, &s)) << s;
  ASSERT_TRUE(tmux.until([](const std::string& x) { return x.find("HITL_EXIT=") != std::string::npos; }, 240s, &s)) << s;
  EXPECT_NE(s.find("demo flown"), std::string::npos) << s;
  EXPECT_NE(s.find("HITL_EXIT=0"), std::string::npos) << s;
}

TEST(TuiE2E, WithoutATerminalSaysSoAndFallsBack) {
  const uint16_t hil = test::free_udp_port();
  auto r = test::run_hitl({"sim", "-i", "127.0.0.1", "--hil-port", std::to_string(hil), "--local-port",
                           std::to_string(test::free_udp_port()), "--no-vio", "--clients", "0", "--duration", "1", "--speed",
                           "0", "--tui"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("--tui: stdout is not a terminal; showing the status lines instead"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("ended: duration"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace hitl
