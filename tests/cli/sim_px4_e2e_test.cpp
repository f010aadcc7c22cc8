// hitl sim --px4 end to end against stand-in PX4 builds (bin/px4 a bash script, etc/init.d-posix/rcS):
// what is not a build, a PX4 that exits before or after it connects, one that never connects, one
// that refuses a parameter, and that neither Ctrl-C nor SIGKILL of hitl leaves a PX4 behind; two
// sessions at once claim different instances; hitl doctor --px4 on a stand-in build and on a folder
// that is not one. Real PX4 flies in tests/px4 (label px4).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>

#include "tests/support/json_lines.h"
#include "tests/support/process.h"

namespace hitl::test {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

/// A stand-in PX4 SITL build in `root`: bin/px4 runs `body` under bash with PX4's arguments
/// (-d -i N -w DIR ETC: the instance is $3).
std::string standin_build(const fs::path& root, const std::string& body) {
  const fs::path b = root / "build";
  write(b / "bin" / "px4", "#!/bin/bash\n" + body);
  ::chmod((b / "bin" / "px4").c_str(), 0755);
  write(b / "etc" / "init.d-posix" / "rcS", "# stand-in\n");
  return b.string();
}

bool gone_within(int pid, std::chrono::milliseconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (process_running(pid)) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(20ms);
  }
  return true;
}

int read_pid(const fs::path& file, std::chrono::milliseconds limit) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < until) {
    std::ifstream in(file);
    int pid = 0;
    if (in >> pid && pid > 0) return pid;
    std::this_thread::sleep_for(20ms);
  }
  return -1;
}

std::vector<std::string> sim_args(const std::string& dir, std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"sim", "--px4", dir, "--no-vio", "--clients", "0"};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(SimPx4E2E, AFolderThatIsNotAPx4BuildSaysWhatIsMissing) {
  const std::string dir = temp_dir();
  const auto r = run_hitl(sim_args(dir));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--px4: '" + dir + "' is not a PX4 SITL build: no bin/px4"), std::string::npos) << r.err;
  const auto missing = run_hitl(sim_args(dir + "/nowhere"));
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_NE(missing.err.find("no such folder"), std::string::npos) << missing.err;
  const auto demo = run_hitl({"demo", "--px4", dir});
  EXPECT_EQ(demo.exit_code, 2) << demo.err;
  EXPECT_NE(demo.err.find("hitl demo: --px4: '" + dir + "' is not a PX4 SITL build"), std::string::npos) << demo.err;
}

TEST(SimPx4E2E, Px4OptionsWithoutPx4AreRefused) {
  const auto r = run_hitl({"sim", "--px4-param", "SYS_FAILURE_EN=1", "--duration", "0.1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("need --px4 DIR"), std::string::npos) << r.err;
  const std::string dir = standin_build(temp_dir(), "exit 0\n");
  const auto bad = run_hitl(sim_args(dir, {"--px4-param", "lower=1"}));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--px4-param 'lower' is not a PX4 parameter name"), std::string::npos) << bad.err;
  const auto fast = run_hitl(sim_args(dir, {"--speed", "0"}));
  EXPECT_EQ(fast.exit_code, 2) << fast.err;
  EXPECT_NE(fast.err.find("--speed 0 with --px4"), std::string::npos) << fast.err;
}

TEST(SimPx4E2E, Px4ThatExitsBeforeConnectingEndsTheSessionWithItsConsole) {
  const std::string dir = standin_build(temp_dir(), "echo 'ERROR [px4] Startup script returned with return value: 256'\nexit 3\n");
  const auto r = run_hitl(sim_args(dir), 30s);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("exited with code 3 before it connected"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Startup script returned with return value: 256"), std::string::npos) << r.err;
}

TEST(SimPx4E2E, Px4ThatNeverConnectsEndsTheSessionAtTheTimeoutAndIsKilled) {
  const fs::path root = temp_dir();
  const std::string dir = standin_build(root, "echo $$ > " + (root / "pid").string() + "\nexec sleep 60\n");
  const auto r = run_hitl(sim_args(dir, {"--px4-timeout", "1"}), 30s);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("did not connect to TCP 127.0.0.1:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("within 1 s"), std::string::npos) << r.err;
  const int pid = read_pid(root / "pid", 1s);
  ASSERT_GT(pid, 0);
  EXPECT_TRUE(gone_within(pid, 2s)) << "the stand-in PX4 " << pid << " outlived the session";
}

TEST(SimPx4E2E, Px4ThatRefusesAParameterEndsTheSessionNamingIt) {
  const std::string dir = standin_build(temp_dir(), "echo 'ERROR [param] Parameter NOPE_PARAM not found.'\n"
                                                     "echo 'ERROR [param] Parameter UXRCE_DDS_KEY not found.'\nexec sleep 60\n");
  const auto r = run_hitl(sim_args(dir, {"--px4-param", "NOPE_PARAM=1"}), 30s);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("has no parameter NOPE_PARAM (set as NOPE_PARAM=1, --px4-param)"), std::string::npos) << r.err;
  // A parameter of a module this build left out, which PX4's own script sets, is not the user's problem.
  EXPECT_EQ(r.err.find("UXRCE_DDS_KEY"), std::string::npos) << r.err;
}

TEST(SimPx4E2E, Px4ThatDiesMidSessionEndsItWithExit1AndItsLastLines) {
  // Connects to the simulator port as PX4 does (4560 + instance), then dies.
  const std::string dir = standin_build(temp_dir(),
                                        "exec 3<>/dev/tcp/127.0.0.1/$((4560 + $3))\nsleep 1\n"
                                        "echo 'ERROR [simulator_mavlink] poll timeout 0, 111'\nexit 7\n");
  const auto r = run_hitl(sim_args(dir), 30s);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("PX4 SITL connected from 127.0.0.1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("exited with code 7 during the session"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("poll timeout 0, 111"), std::string::npos) << r.err;
}

/// hitl sim --px4 with a stand-in that stays; the stand-in's pid once it started.
struct RunningSession {
  fs::path root = temp_dir();
  std::unique_ptr<Process> sim;
  int px4_pid = -1;
  RunningSession() {
    const std::string dir = standin_build(root, "echo $$ > " + (root / "pid").string() + "\nexec sleep 60\n");
    std::vector<std::string> argv = {hitl_binary()};
    for (const auto& a : sim_args(dir, {"--px4-timeout", "60"})) argv.push_back(a);
    sim = std::make_unique<Process>(argv);
    px4_pid = read_pid(root / "pid", 10s);
  }
};

TEST(SimPx4E2E, CtrlCOfHitlStopsItsPx4) {
  RunningSession s;
  ASSERT_GT(s.px4_pid, 0) << s.sim->err();
  s.sim->signal(SIGINT);
  EXPECT_EQ(s.sim->wait(15s), 0) << s.sim->err();
  EXPECT_TRUE(gone_within(s.px4_pid, 2s)) << "PX4 " << s.px4_pid << " outlived hitl's Ctrl-C";
  EXPECT_NE(s.sim->err().find("stopped PX4"), std::string::npos) << s.sim->err();
}

TEST(SimPx4E2E, KillOfHitlLeavesNoPx4Behind) {
  RunningSession s;
  ASSERT_GT(s.px4_pid, 0) << s.sim->err();
  s.sim->signal(SIGKILL);
  s.sim->wait(5s);
  EXPECT_TRUE(gone_within(s.px4_pid, 2s)) << "PX4 " << s.px4_pid << " outlived hitl's SIGKILL";
}

TEST(SimPx4E2E, KillOfHitlLeavesNothingPx4StartedBehind) {
  // PX4 runs its start script in a shell that starts PX4's modules as client processes: killed with
  // PX4 alone, that shell went on and started them in the next PX4 of the same instance ("Task
  // already running", "ekf2 alloc and init failed"). Everything in PX4's process group goes.
  const fs::path root = temp_dir();
  const std::string dir = standin_build(root, "(trap '' TERM; echo $BASHPID > " + (root / "script").string() +
                                                  "; exec sleep 60) &\necho $$ > " + (root / "pid").string() +
                                                  "\nexec sleep 60\n");
  Process sim({hitl_binary(), "sim", "--px4", dir, "--no-vio", "--clients", "0", "--px4-timeout", "60"});
  const int px4 = read_pid(root / "pid", 10s), script = read_pid(root / "script", 10s);
  ASSERT_GT(px4, 0) << sim.err();
  ASSERT_GT(script, 0) << sim.err();
  sim.signal(SIGKILL);
  sim.wait(5s);
  EXPECT_TRUE(gone_within(px4, 2s)) << "PX4 " << px4 << " outlived hitl's SIGKILL";
  EXPECT_TRUE(gone_within(script, 2s)) << "PX4's start script " << script << " outlived hitl's SIGKILL";
}

TEST(SimPx4E2E, TwoSessionsAtOnceClaimDifferentInstances) {
  RunningSession a, b;
  ASSERT_GT(a.px4_pid, 0) << a.sim->err();
  ASSERT_GT(b.px4_pid, 0) << b.sim->err();
  const std::regex instance("started PX4 as instance ([0-9]+)");
  std::smatch ma, mb;
  const std::string ea = a.sim->err(), eb = b.sim->err();
  ASSERT_TRUE(std::regex_search(ea, ma, instance)) << ea;
  ASSERT_TRUE(std::regex_search(eb, mb, instance)) << eb;
  EXPECT_NE(ma[1].str(), mb[1].str());
  a.sim->signal(SIGINT);
  b.sim->signal(SIGINT);
  a.sim->wait(15s);
  b.sim->wait(15s);
}

TEST(SimPx4E2E, DoctorChecksAPx4BuildAndTheInstanceItWouldTake) {
  // hitl doctor --px4 DIR with no session: the build (a stand-in says no version: warn), the instance
  // hitl sim --px4 would take; a folder that is not a build fails naming what is missing.
  const std::string dir = standin_build(temp_dir(), "exit 0\n");
  auto doctor = [](const std::string& px4) {
    return run_hitl({"--json", "doctor", "-i", "127.0.0.1", "--port", std::to_string(free_udp_port()), "--session-port",
                     std::to_string(free_udp_port()), "--timeout", "1", "--listen", "1.2", "--px4", px4},
                    60s);
  };
  auto checks = [](const RunResult& r) {
    std::map<std::string, nlohmann::json> by_id;
    for (const auto& j : json_lines(r.out))
      if (j.value("type", "") == "check") by_id[j["check"]] = j;
    return by_id;
  };
  auto found = checks(doctor(dir));
  EXPECT_EQ(found["px4-build"]["result"], "warn") << found["px4-build"].dump();
  EXPECT_NE(found["px4-build"]["saw"].get<std::string>().find(dir), std::string::npos) << found["px4-build"].dump();
  EXPECT_NE(found["px4-instance"]["result"], "fail") << found["px4-instance"].dump();
  EXPECT_NE(found["px4-instance"]["saw"].get<std::string>().find("hitl sim --px4 takes instance"), std::string::npos)
      << found["px4-instance"].dump();
  EXPECT_EQ(found["px4-connected"]["result"], "skip");
  auto missing = checks(doctor(temp_dir()));
  EXPECT_EQ(missing["px4-build"]["result"], "fail") << missing["px4-build"].dump();
  EXPECT_NE(missing["px4-build"]["saw"].get<std::string>().find("no bin/px4"), std::string::npos) << missing["px4-build"].dump();
  auto bad = run_hitl({"doctor", "--px4-param", "NOT A PARAM"});
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--px4-param"), std::string::npos) << bad.err;
}


}  // namespace
}  // namespace hitl::test
