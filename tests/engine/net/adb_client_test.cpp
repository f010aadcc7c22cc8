// adb as hitl uses it (engine/net/adb_client.h), the program runner under it, and which machine an
// executable is for (what hitl pushes to the board).
#include <gtest/gtest.h>

#include <sys/utsname.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>

#include "engine/net/adb_client.h"
#include "engine/net/child_process.h"
#include "engine/net/executable_arch.h"
#include "tests/support/process.h"

namespace hitl::net {
namespace {

/// Sets $PATH for one test and puts it back.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& path) : old_(std::getenv("PATH") ? std::getenv("PATH") : "") { ::setenv("PATH", path.c_str(), 1); }
  ~ScopedPath() { ::setenv("PATH", old_.c_str(), 1); }

 private:
  std::string old_;
};

TEST(AdbDevices, ParsesDevicesAndSkipsTheServerLines) {
  const auto d = parse_adb_devices(
      "* daemon not running; starting now at tcp:5037\n"
      "* daemon started successfully\n"
      "List of devices attached\n"
      "f3a9c0d2\tdevice\n"
      "7b1e\tunauthorized\n"
      "0123456789ABCDEF\tno permissions (user in plugdev group; are your udev rules wrong?); see [http://developer.android.com/tools/device.html]\n"
      "emulator-5554   offline\n"
      "\n");
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[0].serial, "f3a9c0d2");
  EXPECT_TRUE(d[0].ready());
  EXPECT_EQ(d[1].state, "unauthorized");
  EXPECT_EQ(d[2].state, "no permissions");
  EXPECT_EQ(d[3].serial, "emulator-5554");
  EXPECT_EQ(d[3].state, "offline");
}

TEST(AdbDevices, LongListingKeepsTheState) {
  const auto d = parse_adb_devices("List of devices attached\nabc123   device usb:1-4 product:qrb5165 model:M0054 transport_id:3\n");
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].serial, "abc123");
  EXPECT_EQ(d[0].state, "device");
  EXPECT_TRUE(parse_adb_devices("List of devices attached\n\n").empty());
}

TEST(AdbDevices, ChoosesTheOnlyReadyOneOrSaysWhatToDo) {
  const std::vector<AdbDevice> one{{"A1", "device"}, {"B2", "offline"}};
  EXPECT_EQ(choose_adb_device(one, "").value(), "A1");
  EXPECT_EQ(choose_adb_device(one, "A1").value(), "A1");

  const auto none = choose_adb_device({}, "");
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("plug in the VOXL2's USB-C cable"), std::string::npos) << none.error().message;
  EXPECT_NE(none.error().message.find("adb devices"), std::string::npos);

  const auto two = choose_adb_device({{"A1", "device"}, {"C3", "device"}}, "");
  ASSERT_FALSE(two);
  EXPECT_EQ(two.error().message, "2 devices are attached to adb (A1, C3): choose the board with --adb-serial SERIAL");

  const auto offline = choose_adb_device(one, "B2");
  ASSERT_FALSE(offline);
  EXPECT_NE(offline.error().message.find("B2 is offline: unplug and replug"), std::string::npos) << offline.error().message;

  const auto missing = choose_adb_device(one, "ZZ");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, "--adb-serial ZZ: no such device attached (`adb devices` lists A1 (device), B2 (offline))");

  const auto unready = choose_adb_device({{"U", "unauthorized"}, {"P", "no permissions"}}, "");
  ASSERT_FALSE(unready);
  EXPECT_NE(unready.error().message.find("U is unauthorized"), std::string::npos);
  EXPECT_NE(unready.error().message.find("udev rule"), std::string::npos);
}

TEST(AdbDevices, ConnectSaysConnectedOnlyWhenItIs) {
  EXPECT_TRUE(adb_connected("connected to 192.168.101.2:5555\n"));
  EXPECT_TRUE(adb_connected("already connected to 192.168.101.2:5555\n"));
  EXPECT_FALSE(adb_connected("failed to connect to '192.168.101.2:5555': Connection refused\n"));
  EXPECT_FALSE(adb_connected("cannot connect to 192.168.101.2:5555: No route to host (113)\n"));
  EXPECT_FALSE(adb_connected(""));
}

TEST(AdbProgram, MissingAdbNamesTheDebianPackage) {
  const auto empty_dir = test::temp_dir();
  ScopedPath path(empty_dir);
  const auto found = find_adb();
  ASSERT_FALSE(found);
  EXPECT_NE(found.error().message.find("install the Debian package adb (sudo apt-get install adb)"), std::string::npos);
  const auto listed = list_adb_devices();
  ASSERT_FALSE(listed);
  EXPECT_EQ(listed.error().message, found.error().message);
}

TEST(AdbProgram, FoundOnPathOnlyWhenExecutable) {
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/adb") << "#!/bin/sh\n";
  ScopedPath path("/nonexistent:" + dir);
  EXPECT_FALSE(find_on_path("adb"));  // not executable yet
  ASSERT_EQ(::chmod((dir + "/adb").c_str(), 0755), 0);
  EXPECT_EQ(find_on_path("adb").value_or(""), dir + "/adb");
  EXPECT_EQ(find_adb().value(), dir + "/adb");
}

TEST(ChildProcess, OutputAndExitCode) {
  const auto r = run_program("/bin/sh", {"-c", "echo out; echo err >&2; exit 3"}, 10000);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->exit_code, 3);
  EXPECT_EQ(r->out, "out\n");
  EXPECT_EQ(r->err, "err\n");
}

TEST(ChildProcess, TimeLimitKills) {
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_program("/bin/sh", {"-c", "sleep 30"}, 300);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("did not finish within 300 ms (killed)"), std::string::npos) << r.error().message;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

TEST(ChildProcess, ADaemonHoldingThePipesDoesNotKeepTheCallWaiting) {
  // What `adb start-server` and `hitl-adb-relay --daemon` do: a child lives on with our pipes.
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_program("/bin/sh", {"-c", "sleep 20 & echo started"}, 15000);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->exit_code, 0);
  EXPECT_EQ(r->out, "started\n");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(ChildProcess, ProgramThatCannotStart) {
  const auto r = run_program("/nonexistent/adb", {"devices"}, 1000);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("'/nonexistent/adb devices': cannot start it"), std::string::npos) << r.error().message;
  EXPECT_EQ(command_line("adb", {"shell", "uname -m"}), "adb shell 'uname -m'");
}

TEST(ExecutableArch, TheRelayIsBuiltForThisMachine) {
  utsname u{};
  ASSERT_EQ(::uname(&u), 0);
  EXPECT_EQ(executable_architecture(HITL_ADB_RELAY_BINARY).value_or("?"), normalize_machine(u.machine));
  const auto dir = test::temp_dir();
  std::ofstream(dir + "/script") << "#!/bin/sh\necho hi\n";
  EXPECT_FALSE(executable_architecture(dir + "/script"));
  EXPECT_FALSE(executable_architecture(dir + "/missing"));
}

TEST(ExecutableArch, UnameWords) {
  EXPECT_EQ(normalize_machine("aarch64"), "aarch64");
  EXPECT_EQ(normalize_machine("arm64"), "aarch64");
  EXPECT_EQ(normalize_machine("armv7l"), "arm");
  EXPECT_EQ(normalize_machine("x86_64"), "x86_64");
  EXPECT_EQ(normalize_machine("i686"), "i386");
}

}  // namespace
}  // namespace hitl::net
