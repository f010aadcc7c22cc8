// target/px4/scripts/voxl-px4-hitl against a fake board: stand-ins for px4 (which runs the
// script as its startup script, as PX4 does: /bin/sh FILE INSTANCE), the px4-* clients,
// voxl-platform and sleep record every call to a log, and HITL_ROOT holds /etc/version, the
// parameter file and the default parameter set. The test checks the ORDER of what was started
// against the spec's Startup Sequence, and the script with shellcheck.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_file.h"
#include "tests/support/process.h"

namespace hitl {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// As the script names itself to px4: its absolute path with symbolic links resolved.
const std::string kScript = std::filesystem::canonical(std::string(HITL_SOURCE_DIR) + "/target/px4/scripts/voxl-px4-hitl").string();

void write_executable(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
  ::chmod(path.c_str(), 0755);
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

class FakeBoard {
 public:
  FakeBoard() : dir_(test::temp_dir()) {
    fs::create_directories(bin());
    fs::create_directories(root() + "/data/px4/param");
    fs::create_directories(root() + "/usr/share/voxl-hitl-px4-scripts");
    fs::copy_file(HITL_PX4_DEFAULTS_CONFIG, root() + "/usr/share/voxl-hitl-px4-scripts/voxl-px4-hitl-set-default-parameters.config");
    // A recording stand-in: logs "name args", fails when the call is the one HITL_FAIL_CALL names.
    const std::string record =
        "#!/bin/sh\n"
        "call=\"$(basename \"$0\") $*\"\n"
        "echo \"$call\" >> \"$HITL_CALL_LOG\"\n"
        "[ \"$call\" = \"${HITL_FAIL_CALL:-}\" ] && exit 3\n"
        "exit 0\n";
    for (const char* name : {"px4-param", "px4-qshell", "px4-mavlink", "px4-dataman", "px4-navigator", "px4-load_mon", "sleep"}) {
      write_executable(bin() + "/" + name, record);
    }
    // px4 runs the -s file as its startup script, the way PX4's posix main does.
    write_executable(bin() + "/px4",
                     "#!/bin/sh\n"
                     "echo \"px4 $*\" >> \"$HITL_CALL_LOG\"\n"
                     "while [ $# -gt 0 ]; do\n"
                     "  if [ \"$1\" = -s ]; then exec /bin/sh \"$2\" 0; fi\n"
                     "  shift\n"
                     "done\n"
                     "exit 1\n");
  }
  void set_platform(const std::string& platform) {
    write_executable(bin() + "/voxl-platform",
                     "#!/bin/sh\necho voxl-platform >> \"$HITL_CALL_LOG\"\n" +
                         (platform.empty() ? std::string("exit 1\n") : "echo " + platform + "\n"));
  }
  void set_etc_version(const std::string& text) {
    fs::create_directories(root() + "/etc");
    std::ofstream(root() + "/etc/version") << text << "\n";
  }
  test::RunResult run(std::vector<std::string> args, const std::string& fail_call = "") {
    std::vector<std::string> argv{"/usr/bin/env", "-i", "PATH=" + bin() + ":/usr/bin:/bin", "HITL_ROOT=" + root(),
                                  "HITL_CALL_LOG=" + log(), "HITL_FAIL_CALL=" + fail_call, kScript};
    argv.insert(argv.end(), args.begin(), args.end());
    test::Process p(argv);
    const int code = p.wait(60s);
    return {code, p.out(), p.err()};
  }
  std::vector<std::string> calls() const { return lines_of(log()); }
  void clear_log() const { fs::remove(log()); }
  std::string root() const { return dir_ + "/root"; }
  std::string bin() const { return dir_ + "/bin"; }
  std::string log() const { return dir_ + "/calls.log"; }
  std::string param_file() const { return root() + "/data/px4/param/hitl_parameters"; }

 private:
  std::string dir_;
};

std::size_t index_of(const std::vector<std::string>& calls, const std::string& call) {
  const auto it = std::find(calls.begin(), calls.end(), call);
  return it == calls.end() ? std::string::npos : static_cast<std::size_t>(it - calls.begin());
}

/// Steps 3 to 9, the same on every boot.
std::vector<std::string> expected_start_sequence() {
  std::vector<std::string> c = {
      // 3. apps-proc modules
      "px4-dataman start", "px4-navigator start", "px4-load_mon start",
      // 4. MAVLink instances (DESIGN.md's port table)
      "px4-mavlink start -x -u 14560 -o 14550 -r 1000000 -m custom",
      "px4-mavlink start -x -u 14556 -o 14557 -r 100000 -n lo -m onboard",
      "px4-mavlink start -x -u 14558 -o 14559 -r 100000",
      // 5-7. dsp_hitl, the 1 s wait, sensors
      "px4-qshell dsp_hitl start", "sleep 1", "px4-qshell sensors start -h",
      // 8. flight stack on the DSP
      "px4-qshell ekf2 start", "px4-qshell mc_hover_thrust_estimator start", "px4-qshell land_detector start multicopter",
      "px4-qshell flight_mode_manager start", "px4-qshell mc_pos_control start", "px4-qshell mc_att_control start",
      "px4-qshell mc_rate_control start", "px4-qshell control_allocator start", "px4-qshell pwm_out_sim start -m hil",
      "px4-qshell rc_update start", "px4-qshell manual_control start", "px4-qshell commander start -h",
      // 9. streams
      "px4-mavlink stream -u 14560 -s HIL_ACTUATOR_CONTROLS -r 200"};
  for (const char* port : {"14560", "14556", "14558"}) {
    const std::string p = port;
    c.push_back("px4-mavlink stream -u " + p + " -s HIGHRES_IMU -r 0");
    c.push_back("px4-mavlink stream -u " + p + " -s SCALED_IMU -r 0");
    c.push_back("px4-mavlink stream -u " + p + " -s ATTITUDE -r 10");
    c.push_back("px4-mavlink stream -u " + p + " -s GLOBAL_POSITION_INT -r 5");
  }
  c.push_back("px4-mavlink boot_complete");
  return c;
}

/// Step 2 on first boot: select the file, every `param set` line of the generated set (checked
/// against hitl-defaults.params by default_parameters_config_test), save.
std::vector<std::string> default_parameter_calls(const std::string& param_file) {
  std::vector<std::string> c{"px4-param select " + param_file};
  for (const auto& line : lines_of(HITL_PX4_DEFAULTS_CONFIG)) {
    if (line.rfind("param set ", 0) == 0) c.push_back("px4-" + line);
    // A parameter some firmware lacks: looked up first, set when this PX4 has it (the stand-in has all).
    if (const std::string ifp = "param set-if-present "; line.rfind(ifp, 0) == 0) {
      const std::string rest = line.substr(ifp.size());
      c.push_back("px4-param find " + rest.substr(0, rest.find(' ')));
      c.push_back("px4-param set " + rest);
    }
  }
  EXPECT_EQ(c.size() - 1, vehicle::hitl_default_params().size() + vehicle::hitl_absent_notes().size());
  c.push_back("px4-param save");
  return c;
}

TEST(VoxlPx4HitlScript, FirstBootRunsTheSpecsStartupSequenceInOrder) {
  FakeBoard board;
  board.set_platform("M0197");
  const auto r = board.run({"start"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("[1/9] running on M0197"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("HITL start sequence complete on M0197"), std::string::npos) << r.out;

  std::vector<std::string> expected{"voxl-platform", "px4 -s " + kScript};
  const auto params = default_parameter_calls(board.param_file());
  expected.insert(expected.end(), params.begin(), params.end());
  const auto start = expected_start_sequence();
  expected.insert(expected.end(), start.begin(), start.end());
  EXPECT_EQ(board.calls(), expected);

  // The orderings the spec insists on, said plainly.
  const auto calls = board.calls();
  const std::size_t mavlink = index_of(calls, "px4-mavlink start -x -u 14560 -o 14550 -r 1000000 -m custom");
  const std::size_t dsp_hitl = index_of(calls, "px4-qshell dsp_hitl start");
  const std::size_t wait = index_of(calls, "sleep 1");
  const std::size_t sensors = index_of(calls, "px4-qshell sensors start -h");
  const std::size_t commander = index_of(calls, "px4-qshell commander start -h");
  const std::size_t actuators = index_of(calls, "px4-mavlink stream -u 14560 -s HIL_ACTUATOR_CONTROLS -r 200");
  ASSERT_NE(sensors, std::string::npos);
  EXPECT_LT(index_of(calls, "px4-param save"), index_of(calls, "px4-dataman start"));
  EXPECT_LT(mavlink, dsp_hitl) << "MAVLink must be running before dsp_hitl starts";
  EXPECT_EQ(wait, dsp_hitl + 1);
  EXPECT_EQ(sensors, wait + 1) << "dsp_hitl, the 1 s wait, then sensors";
  EXPECT_LT(sensors, index_of(calls, "px4-qshell ekf2 start"));
  EXPECT_LT(commander, actuators);
}

// On a PX4 without COM_ARM_EKF_POS (v1.16), its line is skipped with a message; the rest loads.
TEST(VoxlPx4HitlScript, FirstBootSkipsAParameterThisPx4Lacks) {
  FakeBoard board;
  board.set_platform("M0197");
  const auto r = board.run({"start"}, "px4-param find COM_ARM_EKF_POS");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("COM_ARM_EKF_POS is not a parameter of this PX4, skipped"), std::string::npos) << r.out;
  const auto calls = board.calls();
  EXPECT_EQ(index_of(calls, "px4-param set COM_ARM_EKF_POS 1.0"), std::string::npos);
  EXPECT_NE(index_of(calls, "px4-param set COM_ARM_EKF_VEL 1.0"), std::string::npos);
  EXPECT_NE(index_of(calls, "px4-param save"), std::string::npos);
}

TEST(VoxlPx4HitlScript, LaterBootsLoadTheSavedParametersAndResetParamsReloadsTheDefaults) {
  FakeBoard board;
  board.set_platform("M0197");
  std::ofstream(board.param_file()) << "saved by px4\n";
  ASSERT_EQ(board.run({"start"}).exit_code, 0);
  auto calls = board.calls();
  ASSERT_GE(calls.size(), 4u);
  EXPECT_EQ(calls[2], "px4-param select " + board.param_file());
  EXPECT_EQ(calls[3], "px4-param load");
  EXPECT_EQ(std::count_if(calls.begin(), calls.end(), [](const std::string& c) { return c.rfind("px4-param set", 0) == 0; }), 0);

  board.clear_log();
  const auto r = board.run({"start", "--reset-params"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(board.param_file()));
  EXPECT_TRUE(fs::exists(board.param_file() + ".bak"));
  calls = board.calls();
  const auto params = default_parameter_calls(board.param_file());
  ASSERT_GE(calls.size(), 2 + params.size());
  EXPECT_EQ(std::vector<std::string>(calls.begin() + 2, calls.begin() + 2 + static_cast<std::ptrdiff_t>(params.size())), params);
}

TEST(VoxlPx4HitlScript, PlatformFromEtcVersionAndRefusalOfAnUnknownBoard) {
  FakeBoard board;
  board.set_platform("");  // voxl-platform fails
  board.set_etc_version("1.7.4 M0054 qrb5165");
  auto r = board.run({});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("running on M0054"), std::string::npos);
  EXPECT_EQ(board.calls().at(1), "px4 -s " + kScript);

  board.clear_log();
  board.set_etc_version("some other computer");
  r = board.run({"start"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cannot tell which board this is"), std::string::npos) << r.err;
  EXPECT_EQ(index_of(board.calls(), "px4 -s " + kScript), std::string::npos) << "px4 must not start";
}

TEST(VoxlPx4HitlScript, AFailingStepStopsTheSequenceAndSaysWhich) {
  FakeBoard board;
  board.set_platform("M0197");
  const auto r = board.run({"start"}, "px4-qshell dsp_hitl start");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("step 5: 'px4-qshell dsp_hitl start' failed (exit 3)"), std::string::npos) << r.err;
  const auto calls = board.calls();
  EXPECT_NE(index_of(calls, "px4-qshell dsp_hitl start"), std::string::npos);
  EXPECT_EQ(index_of(calls, "px4-qshell sensors start -h"), std::string::npos) << "sensors must not start without dsp_hitl";
}

TEST(VoxlPx4HitlScript, DaemonModeUsageAndMissingPieces) {
  FakeBoard board;
  board.set_platform("M0104");
  ASSERT_EQ(board.run({"start", "--daemon"}).exit_code, 0);
  EXPECT_EQ(board.calls().at(1), "px4 -d -s " + kScript);

  auto r = board.run({"--bogus"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown argument '--bogus'"), std::string::npos);
  r = board.run({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("qshell dsp_hitl start"), std::string::npos);

  fs::remove(board.root() + "/usr/share/voxl-hitl-px4-scripts/voxl-px4-hitl-set-default-parameters.config");
  r = board.run({"start"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("HITL default parameters are missing"), std::string::npos) << r.err;
  fs::remove(board.bin() + "/px4");
  r = board.run({"start"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("px4 is not installed"), std::string::npos) << r.err;
}

TEST(VoxlPx4HitlScript, IsShellcheckClean) {
  test::Process which({"/bin/sh", "-c", "command -v shellcheck"});
  ASSERT_EQ(which.wait(20s), 0) << "shellcheck is missing: scripts/install-deps.sh --test installs it";
  test::Process check({"/bin/sh", "-c", "shellcheck -s sh \"$0\"", kScript});
  EXPECT_EQ(check.wait(60s), 0) << check.out() << check.err();
  // The packages' maintainer scripts too.
  const std::string debian = std::string(HITL_SOURCE_DIR) + "/target/debian";
  test::Process maintainer({"/bin/sh", "-c",
                            "cd \"$0\" && shellcheck -s sh voxl-hitl-vio-server/postinst voxl-hitl-vio-server/prerm "
                            "voxl-hitl-vio-server/postrm voxl-hitl-px4-scripts/preinst voxl-hitl-px4-scripts/postrm",
                            debian});
  EXPECT_EQ(maintainer.wait(60s), 0) << maintainer.out() << maintainer.err();
}

}  // namespace
}  // namespace hitl
