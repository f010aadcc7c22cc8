// engine/px4 against a stand-in PX4 build (a shell script as bin/px4): finding a build, the
// parameters, the environment and arguments PX4 gets, its console, and stopping it (SIGTERM, or
// SIGKILL when it ignores SIGTERM as PX4 does before its first HIL_SENSOR), its children too.
#include <gtest/gtest.h>

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "engine/px4/px4_build.h"
#include "engine/px4/px4_instance.h"
#include "engine/px4/px4_process.h"

namespace hitl::px4 {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "hitl-px4-test-XXXXXX").string();
    path = ::mkdtemp(t.data());
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

void write(const fs::path& p, const std::string& text, bool executable = false) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
  if (executable) fs::permissions(p, fs::perms::owner_all, fs::perm_options::add);
}

/// A build folder whose bin/px4 is `script`.
fs::path standin_build(const fs::path& root, const std::string& script) {
  const fs::path b = root / "build" / "px4_sitl_default";
  write(b / "bin" / "px4", "#!/bin/sh\n" + script, true);
  write(b / "etc" / "init.d-posix" / "rcS", "# stand-in\n");
  write(b / "src" / "lib" / "version" / "build_git_version.h", "#define PX4_GIT_TAG_STR  \"v1.16.0\"\n");
  fs::create_directories(root / "boards" / "px4" / "sitl");
  return b;
}

bool wait_for(const std::function<bool()>& done, std::chrono::milliseconds limit = 5s) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return done();
}

std::string all_lines(Px4Console& c) {
  std::string text;
  for (const auto& l : c.new_lines()) text += l + "\n";
  return text;
}

TEST(Px4Build, FoundFromTheTreeOrTheBuildFolder) {
  TempDir d;
  const auto b = standin_build(d.path, "exit 0\n");
  for (const auto& dir : {d.path.string(), b.string()}) {
    auto found = find_px4_build(dir);
    ASSERT_TRUE(found.ok()) << found.error().message;
    EXPECT_EQ(found->program, (b / "bin" / "px4").string());
    EXPECT_EQ(found->etc_dir, (b / "etc").string());
    EXPECT_EQ(found->version, "v1.16.0");
    EXPECT_TRUE(found->lockstep);
  }
}

TEST(Px4Build, WhatIsMissingIsSaid) {
  TempDir d;
  auto none = find_px4_build((d.path / "nothing").string());
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().kind, ErrorKind::Input);
  EXPECT_NE(none.error().message.find("no such folder"), std::string::npos) << none.error().message;

  auto empty = find_px4_build(d.path.string());
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().message.find("no bin/px4"), std::string::npos) << empty.error().message;

  fs::create_directories(d.path / "boards" / "px4" / "sitl");
  auto unbuilt = find_px4_build(d.path.string());
  ASSERT_FALSE(unbuilt.ok());
  EXPECT_NE(unbuilt.error().message.find("scripts/px4-sitl.sh"), std::string::npos) << unbuilt.error().message;

  write(d.path / "bin" / "px4", "#!/bin/sh\n", true);
  auto no_etc = find_px4_build(d.path.string());
  ASSERT_FALSE(no_etc.ok());
  EXPECT_NE(no_etc.error().message.find("no etc/"), std::string::npos) << no_etc.error().message;
}

TEST(Px4Param, NamesAndValuesAreChecked) {
  auto ok = parse_px4_param("MPC_THR_HOVER=0.6");
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->name, "MPC_THR_HOVER");
  EXPECT_EQ(ok->value, "0.6");
  for (const char* bad : {"MPC_THR_HOVER", "=1", "mpc_thr_hover=1", "A_NAME_TOO_LONG_FOR_PX4=1", "X=", "X=abc",
                          "X=nan", "X=1e999", "X;rm=1", "X=1;reboot"}) {
    auto r = parse_px4_param(bad);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.error().kind, ErrorKind::Input) << bad;
  }
}

TEST(Px4Process, StartsPx4WithTheInstanceTheAirframeAndTheParameters) {
  TempDir d;
  standin_build(d.path,
                "echo \"args: $*\"\n"
                "echo \"cwd: $(pwd)\"\n"
                "env | grep -E '^PX4_' | sort\n"
                "printf 'WARN  [health_and_arming_checks] Preflight: GPS fix too low\\n'\n"
                "printf '\\033[1;31mERROR \\033[0m[simulator_mavlink] poll timeout 0, 22\\n'\n"
                "exec sleep 30\n");
  auto build = find_px4_build(d.path.string());
  ASSERT_TRUE(build.ok());
  ::setenv("PX4_SIM_HOSTNAME", "elsewhere", 1);
  Px4StartOptions o;
  o.instance.index = 3;
  o.work_dir = (d.path / "work").string();
  o.console_path = (d.path / "px4.log").string();
  o.params = {{"MPC_THR_HOVER", "0.59"}, {"CA_ROTOR_COUNT", "4"}};
  o.speed_factor = 10;
  auto p = Px4Process::start(*build, o);
  ::unsetenv("PX4_SIM_HOSTNAME");
  ASSERT_TRUE(p.ok()) << p.error().message;
  std::string console;
  ASSERT_TRUE(wait_for([&] {
    console += all_lines((*p)->console());
    return console.find("poll timeout") != std::string::npos;
  })) << console;
  EXPECT_NE(console.find("args: -d -i 3 -w " + o.work_dir + " " + build->etc_dir), std::string::npos) << console;
  EXPECT_NE(console.find("cwd: " + o.work_dir), std::string::npos) << console;
  for (const char* e : {"PX4_PARAM_MPC_THR_HOVER=0.59", "PX4_PARAM_CA_ROTOR_COUNT=4", "PX4_SIM_MODEL=none_iris",
                        "PX4_SYS_AUTOSTART=10016", "PX4_SIM_SPEED_FACTOR=10"})
    EXPECT_NE(console.find(e), std::string::npos) << e << "\n" << console;
  EXPECT_EQ(console.find("PX4_SIM_HOSTNAME"), std::string::npos) << console;
  EXPECT_NE(console.find("ERROR [simulator_mavlink]"), std::string::npos) << "colour codes removed\n" << console;
  EXPECT_FALSE((*p)->exited());
  EXPECT_EQ((*p)->stop(false), 128 + SIGTERM);
  EXPECT_EQ((*p)->stop(false), 128 + SIGTERM);  // again: the same answer, nothing signalled
}

TEST(Px4Process, ConsoleLinesAreClassifiedAsPx4WritesThem) {
  EXPECT_EQ(px4_console_severity("WARN  [commander] Failsafe activated"), Severity::Warning);
  EXPECT_EQ(px4_console_severity("\x1b[1;33mWARN \x1b[0m [ekf2] GPS data stopped"), Severity::Warning);
  EXPECT_EQ(px4_console_severity("ERROR [param] Parameter NO_SUCH not found."), Severity::Error);
  EXPECT_EQ(px4_console_severity("INFO  [commander] Ready for takeoff!"), std::nullopt);
  EXPECT_EQ(px4_console_severity("pxh> "), std::nullopt);
  // A MAVLink shell session (hitl shell) leaves PX4's prompt before the next console line.
  EXPECT_EQ(px4_console_severity("pxh> ERROR [vehicle_air_data] BARO #0 failed:  STALE!"), Severity::Error);
  EXPECT_EQ(px4_console_severity("pxh> pxh> WARN  [failure] inject failure unit: gps"), Severity::Warning);
  EXPECT_EQ(without_shell_prompt("pxh> ERROR [x] y"), "ERROR [x] y");
  EXPECT_EQ(px4_unknown_parameter("ERROR [param] Parameter NOPE_PARAM not found."), "NOPE_PARAM");
  EXPECT_EQ(px4_unknown_parameter("ERROR [param] Parameter  not found."), std::nullopt);
  EXPECT_EQ(px4_unknown_parameter("INFO  [param] selected parameter default file"), std::nullopt);
}

TEST(Px4Process, OnePx4ThatIgnoresSigtermIsKilledWithWhatItStarted) {
  TempDir d;
  const fs::path child_pid = d.path / "child.pid";
  standin_build(d.path, "trap '' TERM INT\n(trap '' TERM; exec sleep 60) &\necho $! > " + child_pid.string() +
                            "\necho started\nwhile :; do sleep 1; done\n");
  auto build = find_px4_build(d.path.string());
  ASSERT_TRUE(build.ok());
  Px4StartOptions o;
  o.work_dir = (d.path / "work").string();
  o.console_path = (d.path / "px4.log").string();
  auto p = Px4Process::start(*build, o);
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_TRUE(wait_for([&] { return fs::exists(child_pid) && fs::file_size(child_pid) > 0; }));
  pid_t grandchild = 0;
  std::ifstream(child_pid) >> grandchild;
  ASSERT_GT(grandchild, 0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ((*p)->stop(false, 0.3), 128 + SIGKILL);  // SIGTERM ignored: killed after the grace
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 10s);
  EXPECT_TRUE(wait_for([&] { return ::kill(grandchild, 0) != 0; })) << "its child outlived it";
}

TEST(Px4Process, ItsEndIsSeenWithItsExitCode) {
  TempDir d;
  standin_build(d.path, "echo 'ERROR [px4] Startup script returned with return value: 256'\nexit 3\n");
  auto build = find_px4_build(d.path.string());
  Px4StartOptions o;
  o.work_dir = (d.path / "work").string();
  o.console_path = (d.path / "px4.log").string();
  auto p = Px4Process::start(*build, o);
  ASSERT_TRUE(p.ok());
  ASSERT_TRUE(wait_for([&] { return (*p)->exited().has_value(); }));
  EXPECT_EQ(*(*p)->exited(), 3);
  const auto last = (*p)->console().last_lines(5);
  ASSERT_EQ(last.size(), 1U);
  EXPECT_NE(last[0].find("return value: 256"), std::string::npos);
}

TEST(Px4Instance, PortsAndBusyInstancesAreNamed) {
  Px4Instance i{5};
  EXPECT_EQ(i.simulator_tcp_port(), 4565);
  EXPECT_EQ(i.gcs_udp_port(), 18575);
  EXPECT_EQ(i.offboard_udp_port(), 14585);
  EXPECT_EQ(i.sysid(), 6);
  EXPECT_EQ(i.lock_file(), "/tmp/px4_lock-5");
  Px4Instance high{Px4Instance::kMax};
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(high.gcs_udp_port());
  a.sin_addr.s_addr = htonl(INADDR_ANY);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0) GTEST_SKIP() << "UDP 18633 is taken here";
  EXPECT_NE(px4_instance_busy(high).find("UDP 18633 (its GCS MAVLink port) is in use"), std::string::npos)
      << px4_instance_busy(high);
  ::close(fd);
}

}  // namespace
}  // namespace hitl::px4
