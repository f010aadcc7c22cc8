// target/px4/sitl without PX4: rcS.hitl run by /bin/sh with stand-ins for PX4's commands (checks
// the spec's startup order and the parameters it loads), and run-hitl-sitl.sh with a stand-in px4
// binary (checks how it starts PX4) and with bad options and unusable builds (checks the refusals).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/process.h"
#include "tests/support/tools.h"

namespace hitl::test {
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;

const fs::path kSitlDir = fs::path(HITL_SOURCE_DIR) / "target" / "px4" / "sitl";
const fs::path kParamsFile = fs::path(HITL_SOURCE_DIR) / "base" / "contract" / "hitl-defaults.params";

void write_file(const fs::path& path, const std::string& text, bool executable = false) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  if (executable) ::chmod(path.c_str(), 0755);
}

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Index of the first line that starts with `prefix`, or -1.
int find_line(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind(prefix, 0) == 0) return static_cast<int>(i);
  }
  return -1;
}

// PX4's commands as shell functions that log their arguments; `param set` remembers values for
// `param greater`; HITL_TEST_FAIL names a command that fails, HITL_TEST_UNKNOWN parameters that
// `param find` does not know, HITL_TEST_REFUSE one that `param set` refuses.
constexpr const char* kAliasStandIn = R"SH(
R="$(pwd)/"
log() { echo "$*" >> "$HITL_TEST_LOG"; }
fails() { [ "${HITL_TEST_FAIL:-}" = "$1" ]; }
param() {
	log "param $*"
	case "$1" in
	find) case " ${HITL_TEST_UNKNOWN:-} " in *" $2 "*) return 1 ;; esac ;;
	set)
		[ "${HITL_TEST_REFUSE:-}" = "$2" ] && return 1
		echo "$2 $3" >> "${R}params.txt"
		;;
	greater) awk -v n="$2" -v limit="$3" '$1 == n { v = $2; found = 1 } END { exit !(found && v > limit) }' "${R}params.txt" ;;
	esac
}
for cmd in mavlink dataman navigator load_mon dsp_hitl sensors commander ekf2 rc_update manual_control \
	land_detector mc_hover_thrust_estimator flight_mode_manager mc_pos_control mc_att_control \
	mc_rate_control control_allocator pwm_out_sim sleep; do
	eval "$cmd() { log \"$cmd \$*\"; ! fails $cmd; }"
done
)SH";

struct RcsRun {
  int exit_code;
  std::string out;
  std::vector<std::string> calls;
};

RcsRun run_rcs(const std::vector<std::string>& env) {
  const fs::path dir = temp_dir();
  write_file(dir / "bin" / "px4-alias.sh", kAliasStandIn);
  write_file(dir / "etc" / "init.d" / "rc.mc_defaults", "log rc.mc_defaults\n");
  const fs::path log = dir / "calls.log";
  std::vector<std::string> argv = {"/usr/bin/env", "PATH=" + (dir / "bin").string() + ":/usr/bin:/bin",
                                   "HITL_TEST_LOG=" + log.string()};
  argv.insert(argv.end(), env.begin(), env.end());
  // rcS.hitl runs in PX4's working directory, where etc/ is PX4's build etc/.
  argv.insert(argv.end(), {"/bin/sh", "-c", "cd '" + dir.string() + "' && exec /bin/sh '" + (kSitlDir / "rcS.hitl").string() + "' 0"});
  Process p(argv);
  const int code = p.wait(seconds(30));
  return {code, p.out() + p.err(), read_lines(log)};
}

TEST(RcsHitl, StartsPx4InTheSpecsOrder) {
  const RcsRun run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const std::vector<std::string> order = {
      "rc.mc_defaults",
      "param set SYS_AUTOSTART 1001",
      "param set SYS_HITL 1",
      "param set PWM_MAIN_FUNC1 101",
      "dataman start",
      "navigator start",
      "load_mon start",
      "mavlink start -x -u 14560 -o 14550",
      "mavlink start -x -u 14556 -o 14557",
      "mavlink start -x -u 14558 -o 14559",
      "dsp_hitl start",
      "sleep 1",
      "sensors start -h",
      "commander start -h",
      "mc_rate_control start",
      "control_allocator start",
      "pwm_out_sim start -m hil",
      "mavlink stream -u 14560 -s HIL_ACTUATOR_CONTROLS -r 200",
      "mavlink stream -u 14560 -s HIGHRES_IMU -r 0",
      "mavlink stream -u 14560 -s SCALED_IMU -r 0",
      "mavlink stream -u 14560 -s ATTITUDE -r 10",
      "mavlink stream -u 14560 -s GLOBAL_POSITION_INT -r 5",
      "mavlink boot_complete",
  };
  int previous = -1;
  for (const std::string& step : order) {
    const int at = find_line(run.calls, step);
    ASSERT_GE(at, 0) << "never ran: " << step << "\n" << run.out;
    EXPECT_GT(at, previous) << "out of order: " << step;
    previous = at;
  }
  EXPECT_NE(find_line(run.calls, "mavlink start -x -u 14556 -o 14557 -r 1000000 -m onboard"), -1);
}

TEST(RcsHitl, SetsEveryParameterOfTheOneDataFile) {
  const RcsRun run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string()});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  int count = 0;
  for (const std::string& line : read_lines(kParamsFile)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string vehicle, component, name, value;
    words >> vehicle >> component >> name >> value;
    EXPECT_NE(find_line(run.calls, "param set " + name + " " + value), -1) << name << " " << value << " was not set";
    ++count;
  }
  EXPECT_GT(count, 40);
  EXPECT_NE(run.out.find(std::to_string(count) + " HITL parameters from"), std::string::npos) << run.out;
}

TEST(RcsHitl, SkipsParametersThisPx4DoesNotHaveAndStopsOnARefusedOne) {
  RcsRun run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string(), "HITL_TEST_UNKNOWN=COM_ARM_EKF_POS COM_ARM_EKF_VEL"});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("not parameters of this PX4, skipped: COM_ARM_EKF_POS COM_ARM_EKF_VEL"), std::string::npos) << run.out;
  EXPECT_EQ(find_line(run.calls, "param set COM_ARM_EKF_POS"), -1);
  EXPECT_NE(find_line(run.calls, "param set COM_ARM_MAG_STR 0 fail"), -1);
  EXPECT_NE(find_line(run.calls, "mavlink boot_complete"), -1);

  run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string(), "HITL_TEST_REFUSE=EKF2_GPS_CTRL"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("param set EKF2_GPS_CTRL 7 failed"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("the HITL parameter set did not load"), std::string::npos) << run.out;
  EXPECT_EQ(find_line(run.calls, "mavlink start"), -1);
}

TEST(RcsHitl, PortsFromTheEnvironment) {
  const RcsRun run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string(), "HITL_HIL_PORT=15560", "HITL_HIL_REMOTE_PORT=15561",
                              "HITL_ONBOARD_PORT=15556", "HITL_ONBOARD_REMOTE_PORT=15557", "HITL_GCS_PORT=15558",
                              "HITL_GCS_REMOTE_PORT=15559"});
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(find_line(run.calls, "mavlink start -x -u 15560 -o 15561"), -1);
  EXPECT_NE(find_line(run.calls, "mavlink start -x -u 15556 -o 15557"), -1);
  EXPECT_NE(find_line(run.calls, "mavlink start -x -u 15558 -o 15559"), -1);
  EXPECT_NE(find_line(run.calls, "mavlink stream -u 15560 -s HIL_ACTUATOR_CONTROLS -r 200"), -1);
}

TEST(RcsHitl, StopsWhenDspHitlDoesNotStart) {
  const RcsRun run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string(), "HITL_TEST_FAIL=dsp_hitl"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("ERROR [hitl] dsp_hitl did not start"), std::string::npos) << run.out;
  EXPECT_EQ(find_line(run.calls, "sensors start"), -1);
  EXPECT_EQ(find_line(run.calls, "commander start"), -1);
}

TEST(RcsHitl, StopsWhenAMavlinkPortIsTaken) {
  const RcsRun run = run_rcs({"HITL_PARAMS_FILE=" + kParamsFile.string(), "HITL_TEST_FAIL=mavlink"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("primary MAVLink instance on UDP 14560 did not start"), std::string::npos) << run.out;
  EXPECT_EQ(find_line(run.calls, "dsp_hitl start"), -1);
}

TEST(RcsHitl, RefusesAMissingOrBadParameterFile) {
  RcsRun run = run_rcs({});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("HITL_PARAMS_FILE is not set"), std::string::npos) << run.out;
  run = run_rcs({"HITL_PARAMS_FILE=/nonexistent/hitl.params"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("cannot read the HITL parameter file /nonexistent/hitl.params"), std::string::npos) << run.out;
  // A file without SYS_HITL: the flight stack would not run in HIL mode.
  const fs::path dir = temp_dir();
  write_file(dir / "no-hitl.params", "1\t1\tSYS_AUTOSTART\t1001\t6\n");
  run = run_rcs({"HITL_PARAMS_FILE=" + (dir / "no-hitl.params").string()});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.out.find("SYS_HITL is not set"), std::string::npos) << run.out;
  EXPECT_EQ(find_line(run.calls, "sensors start"), -1);
}

// run-hitl-sitl.sh with a stand-in PX4 build whose bin/px4 records how it was started.
struct FakeBuild {
  fs::path dir;
  fs::path record;
};

FakeBuild fake_build(bool with_dsp_hitl = true) {
  FakeBuild b{fs::path(temp_dir()) / "build", {}};
  b.record = b.dir.parent_path() / "px4-started.txt";
  write_file(b.dir / "bin" / "px4",
             "#!/bin/sh\n{ echo \"args $*\"; echo \"cwd $(pwd)\"; echo \"pid $$\"; echo \"uptime $(cut -d. -f1 /proc/uptime)\"; "
             "env | grep '^HITL_' | sort; } > '" + b.record.string() + "'\n",
             true);
  if (with_dsp_hitl) write_file(b.dir / "bin" / "px4-dsp_hitl", "", true);
  fs::create_directories(b.dir / "etc" / "init.d");
  return b;
}

RunResult run_script(const std::vector<std::string>& args) {
  std::vector<std::string> argv = {(kSitlDir / "run-hitl-sitl.sh").string()};
  argv.insert(argv.end(), args.begin(), args.end());
  Process p(argv);
  const int code = p.wait(seconds(30));
  return {code, p.out(), p.err()};
}

TEST(RunHitlSitl, StartsPx4WithTheHitlStartupScript) {
  const FakeBuild build = fake_build();
  const fs::path work = build.dir.parent_path() / "work";
  const RunResult r = run_script({"--px4-build", build.dir.string(), "--workdir", work.string(), "--hil-port", "15560",
                                  "--hil-remote-port", "15561", "--gcs-port", "15558", "--daemon"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> started = read_lines(build.record);
  ASSERT_FALSE(started.empty()) << r.err;
  EXPECT_EQ(started[0], "args -d -i 0 -w " + fs::canonical(work).string() + " -s " + (kSitlDir / "rcS.hitl").string() + " " +
                            fs::canonical(build.dir).string() + "/etc");
  EXPECT_NE(find_line(started, "cwd " + fs::canonical(work).string()), -1);
  EXPECT_NE(find_line(started, "HITL_PARAMS_FILE=" + fs::canonical(kParamsFile).string()), -1);
  EXPECT_NE(find_line(started, "HITL_HIL_PORT=15560"), -1);
  EXPECT_NE(find_line(started, "HITL_HIL_REMOTE_PORT=15561"), -1);
  EXPECT_NE(find_line(started, "HITL_ONBOARD_PORT=14556"), -1);
  EXPECT_NE(find_line(started, "HITL_GCS_PORT=15558"), -1);
}

TEST(RunHitlSitl, RefusesWhatCannotWork) {
  const FakeBuild good = fake_build();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const FakeBuild no_module = fake_build(false);
  const FakeBuild lockstep = fake_build();
  write_file(lockstep.dir / "build.ninja", "FLAGS = -DENABLE_LOCKSTEP_SCHEDULER -DFOO\n");
  const std::vector<Case> cases = {
      {{"--px4-build", "/nonexistent/build"}, "/nonexistent/build/bin/px4 does not exist"},
      {{"--px4-build", no_module.dir.string()}, "has no dsp_hitl: build PX4 with target/px4"},
      {{"--px4-build", lockstep.dir.string()}, "is a lockstep build"},
      {{"--px4-build", good.dir.string(), "--hil-port", "0"}, "--hil-port must be a UDP port 1..65535, not '0'"},
      {{"--px4-build", good.dir.string(), "--gcs-port", "14560x"}, "--gcs-port must be a UDP port"},
      {{"--px4-build", good.dir.string(), "--gcs-port", "14560"}, "must differ"},
      {{"--px4-build", good.dir.string(), "--params", "/nonexistent.params"}, "cannot read the parameter file /nonexistent.params"},
      {{"--px4-build", good.dir.string(), "--instance", "x"}, "--instance must be a number"},
      {{"--px4-build", good.dir.string(), "--bogus", "1"}, "unknown option '--bogus'"},
      {{"--px4-build"}, "--px4-build needs a value"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_script(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.message << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << r.err;
    EXPECT_FALSE(fs::exists(good.record)) << "PX4 started despite: " << c.message;
  }
}

// Issue 38 (5b): PX4 without lockstep reads the host's CLOCK_MONOTONIC, and below 2^32 us of uptime
// its IMU integration took the first sample as minutes long, stalling EKF2. On a host up less than
// two hours the script runs PX4 with its clock from 7200 s, in the script's own process (PX4 gets
// the signals sent to it). Made to happen here by running the script where the clock reads 1000 s.
TEST(RunHitlSitl, StartsPx4WithItsClockPastTheIntegratorsLimitOnAFreshHost) {
  if (find_program("unshare").empty() || find_program("nsenter").empty()) GTEST_SKIP() << "no unshare/nsenter (util-linux)";
  const std::string offset = std::to_string(1000 - std::stol(read_text("/proc/uptime")));
  // A namespace where the clock reads 1000 s: as root, or in a user namespace as the script falls back to.
  std::vector<std::string> fresh_host;
  for (const std::vector<std::string>& user_ns : {std::vector<std::string>{}, {"--user", "--map-root-user"}}) {
    std::vector<std::string> cmd = {find_program("unshare")};
    cmd.insert(cmd.end(), user_ns.begin(), user_ns.end());
    cmd.insert(cmd.end(), {"--time", "--monotonic", offset, "--boottime", offset, "--fork"});
    std::vector<std::string> probe = cmd;
    probe.push_back("true");
    if (run_program(probe).exit_code == 0) {
      fresh_host = cmd;
      break;
    }
  }
  if (fresh_host.empty()) GTEST_SKIP() << "no time namespace can be made on this machine (unshare --time)";
  const FakeBuild build = fake_build();
  std::vector<std::string> argv = fresh_host;
  argv.insert(argv.end(), {"sh", "-c", "echo \"script $$ $(cut -d. -f1 /proc/uptime)\"; exec \"$0\" \"$@\"",
                           (kSitlDir / "run-hitl-sitl.sh").string(), "--px4-build", build.dir.string(), "--workdir",
                           (build.dir.parent_path() / "work").string(), "--daemon"});
  Process p(argv);
  ASSERT_EQ(p.wait(seconds(30)), 0) << p.err();
  std::istringstream script_line(p.out());
  std::string word, script_pid;
  long script_uptime_s = -1;
  script_line >> word >> script_pid >> script_uptime_s;
  EXPECT_LT(script_uptime_s, 1100) << p.out();  // the script saw a fresh host
  std::string px4_pid;
  long px4_uptime_s = -1;
  for (const auto& line : read_lines(build.record)) {
    if (line.rfind("uptime ", 0) == 0) px4_uptime_s = std::stol(line.substr(7));
    if (line.rfind("pid ", 0) == 0) px4_pid = line.substr(4);
  }
  EXPECT_GE(px4_uptime_s, 7200) << "PX4's clock must start past 2^32 us (4295 s)";
  EXPECT_EQ(px4_pid, script_pid) << "PX4 must be the script's own process (exec), to get the signals sent to it";
  EXPECT_NE(p.err().find("PX4's clock starts at 7200 s"), std::string::npos) << p.err();
}

TEST(RunHitlSitl, HelpNamesEveryOption) {
  const RunResult r = run_script({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option : {"--px4-build", "--workdir", "--params", "--hil-port", "--hil-remote-port", "--onboard-port",
                             "--onboard-remote-port", "--gcs-port", "--gcs-remote-port", "--instance", "--daemon"}) {
    EXPECT_NE(r.out.find(option), std::string::npos) << option;
  }
}

}  // namespace
}  // namespace hitl::test
