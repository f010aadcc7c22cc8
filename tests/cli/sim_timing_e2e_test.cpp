// hitl sim end to end, the timing options (docs/sim.md "Timing at the board"): --realtime without
// the privilege says so and runs on; with it the loop runs under SCHED_FIFO; --spin-us keeps every
// tick and is range-checked. Nothing here asserts a speed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "tests/cli/sim_board.h"

namespace hitl {
namespace {

using namespace sim_e2e;

/// The scheduling policy of a running process (/proc/PID/stat field 41; 1 = SCHED_FIFO).
int policy_of(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  std::istringstream fields(line.substr(line.rfind(')') + 2));
  std::string f;
  for (int i = 3; i <= 41 && fields >> f; ++i)
    if (i == 41) return std::stoi(f);
  return -1;
}

TEST(SimTimingE2E, RealtimeWithoutThePrivilegeSaysSoAndRuns) {
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  // No locked memory and no real-time priority allowed; as root, also without CAP_SYS_NICE and
  // CAP_IPC_LOCK (which override those limits).
  std::vector<std::string> args{"/usr/bin/prlimit", "--memlock=0:0", "--rtprio=0:0", "--"};
  if (geteuid() == 0)
    args.insert(args.end(), {"/usr/bin/setpriv", "--inh-caps=-sys_nice,-ipc_lock", "--bounding-set=-sys_nice,-ipc_lock", "--"});
  for (auto& a : board.sim_args({"--realtime", "--duration", "1"})) args.push_back(a);
  Process sim(args);
  const int code = sim.wait(30s);
  EXPECT_EQ(code, 0) << sim.err();
  EXPECT_NE(sim.err().find("--realtime: SCHED_FIFO not permitted, mlockall not permitted (run as root or grant "
                           "CAP_SYS_NICE and CAP_IPC_LOCK)"),
            std::string::npos)
      << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["end"], "duration");
  EXPECT_EQ(j["sent"]["HIL_SENSOR"]["count"].get<int>(), 250);  // ran on: every tick of the second
}

TEST(SimTimingE2E, RealtimeWhenPermittedRunsTheLoopUnderSchedFifo) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root (or CAP_SYS_NICE and CAP_IPC_LOCK)";
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--realtime", "--duration", "3"}));
  ASSERT_TRUE(sim.wait_for_stderr("--realtime: SCHED_FIFO granted, mlockall granted", 10s)) << sim.err();
  EXPECT_EQ(policy_of(sim.pid()), 1);  // SCHED_FIFO
  EXPECT_EQ(sim.wait(30s), 0) << sim.err();
}

TEST(SimTimingE2E, SpinUsKeepsEveryTickAndIsRangeChecked) {
  auto too_long = test::run_hitl({"sim", "--spin-us", "5000", "--clients", "0"});
  EXPECT_EQ(too_long.exit_code, 2);
  EXPECT_NE(too_long.err.find("--spin-us"), std::string::npos) << too_long.err;
  EXPECT_EQ(test::run_hitl({"sim", "--spin-us", "-1", "--clients", "0"}).exit_code, 2);
  Board board;
  board.serve([](const msg::HilSensor&, uint64_t) { return std::nullopt; });
  Process sim(board.sim_args({"--spin-us", "300", "--duration", "1"}));
  EXPECT_EQ(sim.wait(30s), 0) << sim.err();
  const auto j = last_json(sim.out());
  EXPECT_EQ(j["sent"]["HIL_SENSOR"]["count"].get<int>(), 250);  // every tick (late ticks depend on the machine's load)
}

}  // namespace
}  // namespace hitl
