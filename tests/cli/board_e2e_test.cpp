// hitl board end to end through the real binary against a stand-in VOXL2: the stand-in adb
// (tests/support/fake_adb.sh) whose push and shell act on a temporary device root, with stand-in
// dpkg, systemctl, systemd-run, journalctl and voxl-px4-hitl (fake_board.sh) that record what
// they are asked, and hitl target as the PX4 on the other end of the MAVLink link.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <fstream>

#include "tests/support/fake_adb.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

/// A vision-hub configuration as a VOXL2 ships it (cJSON's tabs), with keys hitl must not touch.
const char* kShippedVisionHub =
    "{\n\t\"config_file_version\":\t1,\n\t\"en_localhost_mavlink_udp\":\tfalse,\n\t\"en_vio\":\ttrue,\n"
    "\t\"vio_pipe\":\t\"qvio\",\n\t\"secondary_vio_pipe\":\t\"ov\",\n\t\"offboard_mode\":\t\"off\",\n"
    "\t\"follow_tag_id\":\t0,\n\t\"figure_eight_move_home\":\ttrue,\n\t\"robot_radius\":\t0.3\n}\n";

std::size_t index_of(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].rfind(prefix, 0) == 0) return i;
  ADD_FAILURE() << "no line starting with '" << prefix << "'";
  return lines.size();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The env var for the stand-in board, set for one test.
struct ScopedEnv {
  std::string name;
  ScopedEnv(std::string n, const std::string& value) : name(std::move(n)) { ::setenv(name.c_str(), value.c_str(), 1); }
  ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

class BoardE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto v = test::run_hitl({"--version"});
    version_ = v.out.substr(v.out.find(' ') + 1);
    version_.erase(version_.find_last_not_of(" \n") + 1);
    debs_ = test::temp_dir();
    for (const char* name : {"voxl-hitl-vio-server", "voxl-hitl-px4-scripts"}) {
      files_.push_back(debs_ + "/" + name + "_" + version_ + "_arm64.deb");
      std::ofstream(files_.back()) << "a stand-in for " << name << "\n";
    }
    fake_.make_board(kShippedVisionHub);
  }
  test::RunResult board(std::vector<std::string> args, bool json = false) {
    std::vector<std::string> a;
    if (json) a.push_back("--json");
    a.push_back("board");
    a.insert(a.end(), args.begin(), args.end());
    return test::run_hitl(a, 90s);
  }
  test::RunResult install(bool dry_run = false) {
    std::vector<std::string> a{"install", "--packages", debs_};
    if (dry_run) a.push_back("--dry-run");
    return board(a);
  }
  std::vector<std::string> link_args(uint16_t gcs) {
    return {"--adb", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port", std::to_string(local_), "--session-port",
            std::to_string(test::free_udp_port())};
  }
  std::string version_, debs_;
  std::vector<std::string> files_;
  uint16_t local_ = test::free_udp_port();
  test::FakeAdb fake_{{}};
};

TEST_F(BoardE2E, InstallDryRunPrintsThePlanThatTheRealRunExecutesAndChangesNothing) {
  const auto dry = install(true);
  ASSERT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.out.find("      $ dpkg -i /tmp/hitl-board/voxl-hitl-vio-server_" + version_ + "_arm64.deb"), std::string::npos) << dry.out;
  EXPECT_NE(dry.out.find("dry run: nothing was changed on the board"), std::string::npos);
  // Only the survey ran: reads.
  for (const auto& call : fake_.board_calls())
    EXPECT_TRUE(call.rfind("dpkg-query -W", 0) == 0 || call.rfind("systemctl is-", 0) == 0) << "the dry run ran " << call;
  EXPECT_EQ(fake_.board_file("/etc/modalai/voxl-vision-hub.conf"), kShippedVisionHub);
  EXPECT_FALSE(fake_.board_file_exists("/data/hitl-board"));
  EXPECT_FALSE(fake_.board_file_exists("/tmp/hitl-board"));

  const auto real = install();
  ASSERT_EQ(real.exit_code, 0) << real.out << real.err;
  // The same step and action lines, in the same order.
  std::vector<std::string> planned, ran;
  for (const auto& l : lines_of(dry.out))
    if (l.find("undo: ") == std::string::npos && l.rfind("dry run", 0) != 0) planned.push_back(l);
  for (const auto& l : lines_of(real.out))
    if (l.rfind("      -> ", 0) != 0 && l.rfind("done: ", 0) != 0) ran.push_back(l);
  EXPECT_EQ(planned, ran);
  EXPECT_NE(real.out.find("done: 7 steps; undo with: hitl board restore"), std::string::npos) << real.out;
}

TEST_F(BoardE2E, InstallEditsVisionHubKeepingEveryOtherKeyBacksItUpAndRestoreGoesBackByteForByte) {
  const auto r = install();
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto hub = nlohmann::ordered_json::parse(fake_.board_file("/etc/modalai/voxl-vision-hub.conf"));
  std::vector<std::string> keys;
  for (const auto& [k, v] : hub.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"config_file_version", "en_localhost_mavlink_udp", "en_vio", "vio_pipe", "secondary_vio_pipe",
                                            "offboard_mode", "follow_tag_id", "figure_eight_move_home", "robot_radius", "en_hitl"}));
  EXPECT_EQ(hub["en_hitl"], true);
  EXPECT_EQ(hub["en_vio"], false);
  EXPECT_EQ(hub["offboard_mode"], "vfc");
  EXPECT_EQ(hub["secondary_vio_pipe"], "ov");
  EXPECT_EQ(hub["robot_radius"], 0.3);
  EXPECT_EQ(fake_.board_file("/data/hitl-board/voxl-vision-hub.conf.orig"), kShippedVisionHub);
  EXPECT_EQ(nlohmann::json::parse(fake_.board_file("/etc/modalai/voxl-hitl-vio-server.conf")),
            nlohmann::json::parse(R"({"receiver_ip": "0.0.0.0", "receiver_port": 14570})"));
  EXPECT_EQ(fake_.board_package("voxl-hitl-vio-server"), version_);
  EXPECT_EQ(fake_.board_package("voxl-hitl-px4-scripts"), version_);
  EXPECT_EQ(fake_.board_service("voxl-hitl-vio-server"), "enabled inactive");
  EXPECT_FALSE(fake_.board_file_exists("/tmp/hitl-board"));
  const auto calls = fake_.board_calls();
  const auto dpkg = index_of(calls, "dpkg -i /tmp/hitl-board/voxl-hitl-vio-server_");
  EXPECT_LT(dpkg, index_of(calls, "systemctl daemon-reload"));
  EXPECT_LT(index_of(calls, "systemctl daemon-reload"), index_of(calls, "systemctl enable voxl-hitl-vio-server"));

  // A second install keeps the first backup (the original), not the edited file.
  ASSERT_EQ(install().exit_code, 0);
  EXPECT_EQ(fake_.board_file("/data/hitl-board/voxl-vision-hub.conf.orig"), kShippedVisionHub);

  const auto restore = board({"restore"});
  ASSERT_EQ(restore.exit_code, 0) << restore.out << restore.err;
  EXPECT_EQ(fake_.board_file("/etc/modalai/voxl-vision-hub.conf"), kShippedVisionHub);
  EXPECT_FALSE(fake_.board_file_exists("/etc/modalai/voxl-hitl-vio-server.conf"));
  EXPECT_EQ(fake_.board_package("voxl-hitl-vio-server"), "");
  EXPECT_EQ(fake_.board_package("voxl-hitl-px4-scripts"), "");
  EXPECT_EQ(fake_.board_service("voxl-vision-hub"), "enabled active");
  EXPECT_EQ(fake_.board_service("voxl-px4"), "enabled active");
  EXPECT_FALSE(fake_.board_file_exists("/data/hitl-board"));
  // Nothing left to restore.
  const auto again = board({"restore"});
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.err.find("nothing to restore"), std::string::npos) << again.err;
}

TEST_F(BoardE2E, AFailureMidwayStopsSaysWhatIsChangedAndHowToUndoIt) {
  const auto r = [&] {
    ScopedEnv fail("FAKE_BOARD_FAIL", "systemctl enable voxl-vision-hub");
    return install();
  }();
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("step 6/7 \"enable the services\" failed: $ systemctl enable voxl-vision-hub: exit 1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the board said:\n  systemctl: error: the stand-in board was told to fail"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("already changed on the board:\n  - record the board as it is"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("  - install the packages\n"), std::string::npos);
  EXPECT_NE(r.err.find("  - enable the services (may be partly done)"), std::string::npos);
  EXPECT_NE(r.err.find("to undo: hitl board restore"), std::string::npos);
  EXPECT_NE(r.err.find("    adb shell 'systemctl disable voxl-hitl-vio-server'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    adb shell 'dpkg --purge voxl-hitl-vio-server voxl-hitl-px4-scripts'"), std::string::npos);
  EXPECT_EQ(r.out.find("[7/7]"), std::string::npos) << "ran past the failure";
  // The undo it names works.
  const auto restore = board({"restore"});
  ASSERT_EQ(restore.exit_code, 0) << restore.err;
  EXPECT_EQ(fake_.board_file("/etc/modalai/voxl-vision-hub.conf"), kShippedVisionHub);
  EXPECT_EQ(fake_.board_package("voxl-hitl-vio-server"), "");
}

TEST_F(BoardE2E, ARestoreThatFailsMidwayFinishesWhenRunAgain) {
  ASSERT_EQ(install().exit_code, 0);
  const auto r = [&] {
    ScopedEnv fail("FAKE_BOARD_FAIL", "dpkg --purge");
    return board({"restore"});
  }();
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("\"remove the HITL packages\" failed: $ dpkg --purge voxl-hitl-vio-server voxl-hitl-px4-scripts: exit 1"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("run hitl board restore again once the failure is fixed"), std::string::npos) << r.err;
  EXPECT_TRUE(fake_.board_file_exists("/data/hitl-board/state"));
  const auto again = board({"restore"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(fake_.board_file("/etc/modalai/voxl-vision-hub.conf"), kShippedVisionHub);
  EXPECT_EQ(fake_.board_package("voxl-hitl-px4-scripts"), "");
  EXPECT_FALSE(fake_.board_file_exists("/data/hitl-board"));
}

// --json: a status object before each step, exactly one summary, last (README's vocabulary).
TEST_F(BoardE2E, JsonIsStatusObjectsPerStepAndOneSummaryLast) {
  const auto failed = [&] {
    ScopedEnv fail("FAKE_BOARD_FAIL", "dpkg -i");
    return board({"install", "--packages", debs_}, true);
  }();
  EXPECT_EQ(failed.exit_code, 1);
  const auto f = nlohmann::json::parse(lines_of(failed.out).back());
  EXPECT_EQ(f["type"], "summary");
  EXPECT_EQ(f["ok"], false);
  EXPECT_EQ(f["failed_step"]["index"], 3);
  EXPECT_EQ(f["failed_step"]["name"], "install the packages");
  EXPECT_NE(f["failed_step"]["board_output"].get<std::string>().find("told to fail"), std::string::npos) << f;
  EXPECT_EQ(f["undo_command"], "hitl board restore");
  EXPECT_EQ(f["undo"], (nlohmann::json{"dpkg --purge voxl-hitl-vio-server voxl-hitl-px4-scripts", "rm -rf /data/hitl-board", "rm -rf /tmp/hitl-board"}));

  // Again: the failed run's record is kept (the board before it), so one step fewer.
  const auto r = board({"install", "--packages", debs_}, true);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 7u) << r.out;
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) {
    const auto j = nlohmann::json::parse(lines[i]);
    EXPECT_EQ(j["type"], "status");
    EXPECT_EQ(j["step"], i + 1);
    EXPECT_EQ(j["of"], 6);
  }
  const auto summary = nlohmann::json::parse(lines.back());
  EXPECT_EQ(summary["type"], "summary");
  EXPECT_EQ(summary["action"], "install");
  EXPECT_EQ(summary["ok"], true);
  EXPECT_EQ(summary["steps_done"], 6);
  EXPECT_EQ(fake_.board_file("/data/hitl-board/voxl-vision-hub.conf.orig"), kShippedVisionHub);
}

// USB alone (no -i, no --connect): start and status reach PX4 through the adb tunnel's GCS channel,
// the real hitl-adb-relay (pushed, as hitl sim --adb does) forwarding to hitl target.
TEST(BoardTunnelE2E, WithoutDashIStartAndStatusReachPx4ThroughTheAdbTunnel) {
  const uint16_t gcs = test::free_udp_port();
  test::Process px4({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(test::free_udp_port()),
                     "--gcs-port", std::to_string(gcs), "--vio-port", "0"});
  ASSERT_TRUE(px4.wait_for_stderr("EMULATED", 10s)) << px4.err();
  test::FakeAdb fake({.relay_args = "--gcs-port " + std::to_string(gcs) + " --gcs-source-port 0 --hil-port " +
                                    std::to_string(test::free_udp_port()) + " --hil-source-port 0 --vio-port " + std::to_string(test::free_udp_port())});
  fake.make_board(kShippedVisionHub);
  const auto debs = test::temp_dir();
  std::vector<std::string> install{"board", "install"};
  for (const char* name : {"voxl-hitl-vio-server_0.1.0_arm64.deb", "voxl-hitl-px4-scripts_0.1.0_arm64.deb"}) {
    std::ofstream(debs + "/" + name) << "a stand-in\n";
    install.push_back(debs + "/" + name);
  }
  ASSERT_EQ(test::run_hitl(install).exit_code, 0);
  const std::vector<std::string> ports{"--local-port", std::to_string(test::free_udp_port()), "--session-port",
                                       std::to_string(test::free_udp_port())};
  auto args = std::vector<std::string>{"board", "start", "--wait", "20"};
  args.insert(args.end(), ports.begin(), ports.end());
  const auto start = test::run_hitl(args, 90s);
  EXPECT_EQ(start.exit_code, 0) << start.out << start.err;
  EXPECT_NE(start.err.find("hitl board start: PX4 through"), std::string::npos) << start.err;
  EXPECT_NE(start.out.find("-> PX4 is up and dsp_hitl is running"), std::string::npos) << start.out;
  args = {"--json", "board", "status"};
  args.insert(args.end(), ports.begin(), ports.end());
  const auto status = test::run_hitl(args, 90s);
  ASSERT_EQ(status.exit_code, 0) << status.err;
  const auto j = nlohmann::json::parse(status.out);
  EXPECT_EQ(j["px4"]["heartbeat"], true) << j["px4"];
  EXPECT_EQ(j["px4"]["dsp_hitl_running"], true);
  EXPECT_TRUE(fake.stop_relays());
  px4.signal(SIGINT);
  px4.wait(10s);
}

// -i IP without --adb: adb over the network (adb connect IP:5555, then that device).
TEST(BoardNetworkE2E, DashIWithoutAdbConnectsOverTheNetworkAndRunsThereOrSaysHowToListen) {
  test::FakeAdb fake({.devices = "127.0.0.1:5555 device"});
  fake.make_board(kShippedVisionHub);
  const auto r = test::run_hitl({"board", "stop", "-i", "127.0.0.1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto calls = fake.calls();
  ASSERT_FALSE(calls.empty());
  EXPECT_EQ(calls[0], "connect 127.0.0.1:5555");
  EXPECT_EQ(fake.find_call("-s 127.0.0.1:5555 shell systemctl stop voxl-vision-hub"), static_cast<int>(calls.size()) - 1) << calls.back();
  EXPECT_EQ(fake.find_call("devices"), -1) << "no USB device lookup";
  ScopedEnv refuse("FAKE_ADB_CONNECT", "refuse");
  const auto refused = test::run_hitl({"board", "status", "-i", "127.0.0.1"});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("adb connect 127.0.0.1:5555: failed to connect"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("adb tcpip 5555"), std::string::npos) << refused.err;
  // --adb with -i: the board's commands over USB, -i only for MAVLink.
  test::FakeAdb usb({});
  usb.make_board(kShippedVisionHub);
  EXPECT_EQ(test::run_hitl({"board", "stop", "--adb", "-i", "127.0.0.1"}).exit_code, 0);
  EXPECT_EQ(usb.find_call("connect"), -1);
  EXPECT_EQ(usb.find_call("-s FAKE0001 shell systemctl stop voxl-vision-hub"), static_cast<int>(usb.calls().size()) - 1);
}

// Issue 34: a dry run over the network touches nothing, `adb connect` included, and the address is
// checked before adb runs at all.
TEST(BoardNetworkE2E, DryRunWithDashINeverRunsAdbConnectAndChecksTheAddress) {
  {
    test::FakeAdb fake({.devices = "127.0.0.1:5555 device"});
    fake.make_board(kShippedVisionHub);
    const auto r = test::run_hitl({"board", "stop", "--dry-run", "-i", "127.0.0.1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("dry run: nothing was changed on the board"), std::string::npos) << r.out;
    EXPECT_EQ(fake.find_call("connect"), -1) << "a dry run ran adb connect";
    EXPECT_NE(fake.find_call("-s 127.0.0.1:5555 shell"), -1) << "the survey reads through the connected device";
  }
  {
    test::FakeAdb fake({.devices = "FAKE0001 device"});
    const auto r = test::run_hitl({"board", "start", "--dry-run", "-i", "127.0.0.1"});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("a dry run does not run `adb connect 127.0.0.1:5555` (it changes nothing), and adb has no device 127.0.0.1:5555 connected"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(fake.find_call("connect"), -1);
  }
  {
    test::FakeAdb fake({.devices = "FAKE0001 device"});
    for (const char* bad : {"no such host.invalid", "192.168.1.1;reboot"}) {
      const auto r = test::run_hitl({"board", "stop", "--dry-run", "-i", bad});
      EXPECT_EQ(r.exit_code, 2) << bad << r.err;
      EXPECT_NE(r.err.find("-i (the board's address): "), std::string::npos) << r.err;
    }
    EXPECT_TRUE(fake.calls().empty()) << fake.calls().front();
  }
}

TEST_F(BoardE2E, InstallWithoutThisBuildsPackagesNamesTheFileItLookedFor) {
  const auto r = board({"install", "--packages", "/nonexistent"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no /nonexistent/voxl-hitl-vio-server_" + version_ + "_arm64.deb"), std::string::npos) << r.err;
  EXPECT_TRUE(fake_.board_calls().empty());
}

TEST_F(BoardE2E, StartWaitsForPx4SetsTheParametersRestartsPx4ForSysHitlThenStartsTheServicesAndStopReverses) {
  const uint16_t gcs = test::free_udp_port();
  test::Process px4({test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", std::to_string(test::free_udp_port()),
                     "--gcs-port", std::to_string(gcs), "--vio-port", "0"});
  ASSERT_TRUE(px4.wait_for_stderr("EMULATED", 10s)) << px4.err();
  ASSERT_EQ(install().exit_code, 0);
  // A parameter that takes effect only when PX4 starts again.
  auto set = test::run_hitl({"params", "-i", "127.0.0.1", "--port", std::to_string(gcs), "--local-port", std::to_string(local_),
                             "--session-port", std::to_string(test::free_udp_port()), "set", "SYS_HITL", "0"});
  ASSERT_EQ(set.exit_code, 0) << set.err;

  auto args = std::vector<std::string>{"start", "--wait", "20"};
  const auto link = link_args(gcs);
  args.insert(args.end(), link.begin(), link.end());
  const auto start = board(args);
  ASSERT_EQ(start.exit_code, 0) << start.out << start.err;
  EXPECT_NE(start.out.find("      -> PX4 is up and dsp_hitl is running"), std::string::npos) << start.out;
  EXPECT_NE(start.out.find("      -> set SYS_HITL"), std::string::npos) << start.out;
  EXPECT_NE(start.out.find("SYS_HITL takes effect only when PX4 starts again: restarting PX4"), std::string::npos) << start.out;
  const auto calls = fake_.board_calls();
  const auto stop_px4 = index_of(calls, "systemctl stop voxl-px4");
  const auto run = index_of(calls, "systemd-run --unit=voxl-px4-hitl /usr/bin/voxl-px4-hitl start --daemon");
  const auto script = index_of(calls, "voxl-px4-hitl start --daemon");
  const auto restart = index_of(calls, "systemctl restart voxl-px4-hitl");
  const auto vio = index_of(calls, "systemctl restart voxl-hitl-vio-server");
  const auto hub = index_of(calls, "systemctl restart voxl-vision-hub");
  EXPECT_LT(stop_px4, run);
  EXPECT_LT(run, script);
  EXPECT_LT(script, restart);
  EXPECT_LT(restart, vio);
  EXPECT_LT(vio, hub);
  EXPECT_EQ(fake_.board_service("voxl-px4"), "enabled inactive");
  EXPECT_EQ(fake_.board_service("voxl-px4-hitl"), "disabled active");
  EXPECT_EQ(fake_.board_service("voxl-vision-hub"), "enabled active");

  args = {"status"};
  args.insert(args.end(), link.begin(), link.end());
  const auto status = board(args, true);
  ASSERT_EQ(status.exit_code, 0) << status.err;
  const auto j = nlohmann::json::parse(status.out);
  EXPECT_EQ(j["type"], "summary");
  EXPECT_EQ(j["command"], "board");
  EXPECT_EQ(j["action"], "status");
  EXPECT_EQ(j["packages"][0]["name"], "voxl-hitl-vio-server");
  EXPECT_EQ(j["packages"][0]["installed"], version_);
  EXPECT_EQ(j["packages"][0]["current"], true);
  EXPECT_EQ(j["services"]["voxl-px4-hitl"]["active"], true);
  EXPECT_EQ(j["services"]["voxl-hitl-vio-server"]["enabled"], true);
  EXPECT_EQ(j["vision_hub"]["en_hitl"], true);
  EXPECT_EQ(j["vision_hub"]["offboard_mode"], "vfc");
  EXPECT_EQ(j["vision_hub_hitl"], true);
  EXPECT_EQ(j["vio_server"]["receiver_port"], 14570);
  EXPECT_EQ(j["record"], true);
  EXPECT_EQ(j["px4"]["heartbeat"], true);
  EXPECT_EQ(j["px4"]["hil_mode"], true);
  EXPECT_EQ(j["px4"]["dsp_hitl_running"], true);
  EXPECT_EQ(j["params"]["checked"], true);
  EXPECT_TRUE(j["params"]["wrong"].empty()) << j["params"];
  EXPECT_EQ(j["ready"], true) << j["not_ready"];

  const auto text = board(args);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("/etc/modalai/voxl-vision-hub.conf: en_vio false, vio_pipe \"qvio\", en_hitl true, offboard_mode \"vfc\"\n"),
            std::string::npos) << text.out;
  EXPECT_NE(text.out.find("PX4: HEARTBEAT, HIL mode, dsp_hitl running\n"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("\nready for hitl sim\n"), std::string::npos) << text.out;

  const auto stop = board({"stop"});
  ASSERT_EQ(stop.exit_code, 0) << stop.err;
  const auto after = fake_.board_calls();
  const auto from = calls.size();
  std::vector<std::string> stops(after.begin() + static_cast<long>(from), after.end());
  std::vector<std::string> changes;
  for (const auto& c : stops)
    if (c.rfind("systemctl stop", 0) == 0) changes.push_back(c);
  EXPECT_EQ(changes, (std::vector<std::string>{"systemctl stop voxl-vision-hub", "systemctl stop voxl-hitl-vio-server", "systemctl stop voxl-px4-hitl"}));
  EXPECT_EQ(fake_.board_service("voxl-px4-hitl"), "disabled inactive");
  EXPECT_EQ(fake_.board_service("voxl-px4"), "enabled active") << "the board as it boots";
  EXPECT_EQ(after.back(), "systemctl start voxl-px4");

  px4.signal(SIGINT);
  px4.wait(10s);
}

TEST_F(BoardE2E, StartWhenPx4NeverAnswersTimesOutWithTheBoardsOwnOutputAndTheUndo) {
  ASSERT_EQ(install().exit_code, 0);
  ScopedEnv px4_error("FAKE_BOARD_PX4_ERROR", "step 5: 'qshell dsp_hitl start' failed (exit 1)");
  auto args = std::vector<std::string>{"start", "--wait", "2", "--timeout", "0.5"};
  const auto link = link_args(test::free_udp_port());  // nothing listens there
  args.insert(args.end(), link.begin(), link.end());
  const auto r = board(args);
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.err.find("\"wait for PX4 and dsp_hitl (up to 2 s)\" failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("PX4 not ready after 2 s"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("  $ journalctl -u voxl-px4-hitl -n 40 --no-pager"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("voxl-px4-hitl: error: step 5: 'qshell dsp_hitl start' failed (exit 1)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("to undo: hitl board stop"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("adb shell 'systemctl start voxl-px4'"), std::string::npos) << r.err;
}

TEST_F(BoardE2E, StartAndStopAndRestoreDryRunsChangeNothing) {
  ASSERT_EQ(install().exit_code, 0);
  const auto before = fake_.board_calls().size();
  for (std::vector<std::string> args : {std::vector<std::string>{"start", "--dry-run", "--reset-params"}, {"stop", "--dry-run"},
                                        {"restore", "--dry-run", "--params", "remove"}}) {
    const auto r = board(args);
    EXPECT_EQ(r.exit_code, 0) << args[0] << r.err;
    EXPECT_NE(r.out.find("dry run: nothing was changed"), std::string::npos) << r.out;
  }
  const auto calls = fake_.board_calls();
  for (std::size_t i = before; i < calls.size(); ++i)
    EXPECT_TRUE(calls[i].rfind("dpkg-query -W", 0) == 0 || calls[i].rfind("systemctl is-", 0) == 0) << "a dry run ran " << calls[i];
  const auto dry = board({"restore", "--dry-run", "--params", "remove"});
  EXPECT_NE(dry.out.find("$ rm -f /data/px4/param/hitl_parameters"), std::string::npos) << dry.out;
  const auto json = board({"start", "--dry-run", "--reset-params"}, true);
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["dry_run"], true);
  EXPECT_EQ(j["steps"], j["plan"].size());
  EXPECT_NE(j["plan"][1]["actions"][0].get<std::string>().find("--reset-params"), std::string::npos) << j["plan"];
  EXPECT_EQ(j["plan"][1]["undo"][0], "systemctl stop voxl-px4-hitl");
}

}  // namespace
}  // namespace hitl
