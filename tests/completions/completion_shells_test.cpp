// The completion scripts as the shells run them: bash completes partial command lines for real
// (the function called with COMP_WORDS/COMP_CWORD set, as bash does on Tab), fish answers
// `complete -C`, zsh parses the script and registers it with compinit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Writes what `hitl completion SHELL` prints to a temporary file and returns its path.
std::string generated_script(const std::string& shell, const std::string& file_name) {
  const auto r = test::run_hitl({"completion", shell});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto path = test::temp_dir() + "/" + file_name;
  test::write_text(path, r.out);
  return path;
}

class BashCompletion : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    script_ = new std::string(generated_script("bash", "hitl.bash"));
    files_ = new std::string(test::temp_dir());
    for (const char* f : {"a.json", "b.json", "notes.txt", "hitl.toml", "sub/c.json"}) test::write_text(*files_ + "/" + f, "{}");
  }
  static void TearDownTestSuite() {
    delete script_;
    delete files_;
  }

  /// COMPREPLY for the words, the cursor on the last one.
  static std::vector<std::string> complete(const std::vector<std::string>& words) {
    std::string cmd = "source " + shell_quoted(*script_) + " || exit 3\nCOMP_WORDS=(";
    for (const auto& w : words) cmd += shell_quoted(w) + " ";
    cmd += ")\nCOMP_CWORD=" + std::to_string(words.size() - 1) + "\n_hitl\nprintf '%s\\n' \"${COMPREPLY[@]}\"\n";
    const auto r = test::run_program({"/bin/bash", "--norc", "--noprofile", "-c", cmd}, 30s);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    return test::lines_of(r.out);
  }

  static std::string* script_;
  static std::string* files_;
};
std::string* BashCompletion::script_ = nullptr;
std::string* BashCompletion::files_ = nullptr;

using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::Not;
using ::testing::UnorderedElementsAre;

TEST_F(BashCompletion, Subcommands) {
  const auto all = complete({"hitl", ""});
  for (const char* c : {"inspect", "sim", "target", "params", "arm", "disarm", "shell", "fly", "completion"})
    EXPECT_THAT(all, Contains(c));
  EXPECT_THAT(all, Not(Contains("reference")));  // hidden
  EXPECT_THAT(complete({"hitl", "in"}), ElementsAre("inspect"));
  EXPECT_THAT(complete({"hitl", "params", "s"}), UnorderedElementsAre("set", "show"));
  EXPECT_THAT(complete({"hitl", "fly", "t"}), UnorderedElementsAre("takeoff", "trajectory"));
}

TEST_F(BashCompletion, Options) {
  EXPECT_THAT(complete({"hitl", "inspect", "--sh"}), ElementsAre("--show"));
  // Global options fall through to every command; the command's own --help is offered once.
  const auto sim = complete({"hitl", "sim", "--"});
  EXPECT_THAT(sim, Contains("--json"));
  EXPECT_THAT(sim, Contains("--trajectory"));
  EXPECT_EQ(std::count(sim.begin(), sim.end(), "--help"), 1);
  // params' connection options work after its subcommands.
  EXPECT_THAT(complete({"hitl", "params", "show", "--con"}), UnorderedElementsAre("--connect", "--config"));
  // Words before the cursor: a global option, then an option's value, are skipped over.
  EXPECT_THAT(complete({"hitl", "--json", "sim", "-i", "192.168.101.2", "--no-"}), UnorderedElementsAre("--no-vio", "--no-noise"));
  const auto after_value = complete({"hitl", "--dialect", "sim", "params", "--"});  // 'sim' is --dialect's value
  EXPECT_THAT(after_value, Contains("--connect"));
  EXPECT_THAT(after_value, Not(Contains("--lockstep")));
}

TEST_F(BashCompletion, OptionValues) {
  EXPECT_THAT(complete({"hitl", "sim", "--protocol-version", ""}), UnorderedElementsAre("1.0", "2.0"));
  // --option=value: bash splits the word at '='.
  EXPECT_THAT(complete({"hitl", "sim", "--protocol-version", "="}), UnorderedElementsAre("1.0", "2.0"));
  EXPECT_THAT(complete({"hitl", "sim", "--protocol-version", "=", "1"}), ElementsAre("1.0"));
  EXPECT_THAT(complete({"hitl", "completion", ""}), UnorderedElementsAre("bash", "zsh", "fish"));
  EXPECT_THAT(complete({"hitl", "sim", "--en-vio-output", ""}), UnorderedElementsAre("true", "false"));
  // A text value offers nothing (not a file, not an option).
  EXPECT_THAT(complete({"hitl", "sim", "--seed", ""}), ElementsAre());
}

TEST_F(BashCompletion, MessageNames) {
  EXPECT_THAT(complete({"hitl", "inspect", "--show", "HEARTB"}), ElementsAre("HEARTBEAT"));
  const auto odo = complete({"hitl", "inspect", "--show", "OD"});
  EXPECT_THAT(odo, Contains("ODOMETRY"));
  EXPECT_THAT(complete({"hitl", "inspect", "--show", "HEARTBEAT,ATTITUDE_T"}), Contains("HEARTBEAT,ATTITUDE_TARGET"));
  EXPECT_THAT(complete({"hitl", "inspect", "--expect", "ODOM"}), ElementsAre("ODOMETRY="));
  const auto all = complete({"hitl", "inspect", "--show", ""});
  for (const char* name : {"HIL_SENSOR", "HIL_GPS", "HIL_ACTUATOR_CONTROLS", "ODOMETRY", "STATUSTEXT"}) EXPECT_THAT(all, Contains(name));
}

// Issue 36: completion did not know fault names. The name completes; its arguments are the user's.
TEST_F(BashCompletion, FaultNames) {
  EXPECT_THAT(complete({"hitl", "sim", "--fault", "gps-l"}), ElementsAre("gps-loss"));
  EXPECT_THAT(complete({"hitl", "sim", "--fault", "mot"}), Contains("motor"));
  const auto all = complete({"hitl", "sim", "--fault", ""});
  for (const char* name : {"gps-loss", "motor", "prop-damage", "imu-vibration", "baro-stuck"}) EXPECT_THAT(all, Contains(name));
  EXPECT_THAT(complete({"hitl", "sim", "--fault", "motor:2"}), ElementsAre());
  EXPECT_THAT(complete({"hitl", "sim", "--fault", "gps-loss@1"}), ElementsAre());
}

TEST_F(BashCompletion, FilesOfTheRightKind) {
  const std::string d = *files_ + "/";
  // -t FILE.json: JSON files and directories, not other files.
  EXPECT_THAT(complete({"hitl", "sim", "-t", d}), UnorderedElementsAre(d + "a.json", d + "b.json", d + "sub"));
  EXPECT_THAT(complete({"hitl", "sim", "--trajectory=", d}), Not(Contains(d + "notes.txt")));
  // --config FILE.toml
  EXPECT_THAT(complete({"hitl", "--config", d}), UnorderedElementsAre(d + "hitl.toml", d + "sub"));
  // A FILE positional: any file.
  EXPECT_THAT(complete({"hitl", "fly", "trajectory", d + "n"}), ElementsAre(d + "notes.txt"));
}

TEST(FishCompletion, ParsesAndCompletesForReal) {
  if (test::find_program("fish").empty()) GTEST_SKIP() << "fish is not installed (scripts/install-deps.sh --test)";
  const auto script = generated_script("fish", "hitl.fish");
  const auto syntax = test::run_program({"fish", "--no-execute", script});
  EXPECT_EQ(syntax.exit_code, 0) << syntax.err;
  auto complete = [&](const std::string& line) {
    const auto r = test::run_program({"fish", "--no-config", "-c", "source " + shell_quoted(script) + "; complete -C" + shell_quoted(line)}, 30s);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> words;
    for (const auto& l : test::lines_of(r.out)) words.push_back(l.substr(0, l.find('\t')));
    return words;
  };
  EXPECT_THAT(complete("hitl in"), Contains("inspect"));
  EXPECT_THAT(complete("hitl params s"), UnorderedElementsAre("set", "show"));
  EXPECT_THAT(complete("hitl sim --protocol-version "), UnorderedElementsAre("1.0", "2.0"));
  EXPECT_THAT(complete("hitl inspect --show HEARTB"), ElementsAre("HEARTBEAT"));
  EXPECT_THAT(complete("hitl sim --fault gps-l"), ElementsAre("gps-loss"));
  EXPECT_THAT(complete("hitl sim --fault motor:"), ElementsAre());
  EXPECT_THAT(complete("hitl params show --con"), Contains("--connect"));
  EXPECT_THAT(complete("hitl --json sim --traj"), Contains("--trajectory"));
}

TEST(ZshCompletion, ParsesAndRegistersWithCompinit) {
  if (test::find_program("zsh").empty()) GTEST_SKIP() << "zsh is not installed (scripts/install-deps.sh --test)";
  const auto dir = test::temp_dir();
  const auto script = generated_script("zsh", "_hitl");
  const auto syntax = test::run_program({"zsh", "-n", script});
  EXPECT_EQ(syntax.exit_code, 0) << syntax.err;
  // A directory on $fpath holding _hitl, as the package installs it: compinit finds #compdef hitl.
  const auto r = test::run_program(
      {"zsh", "-f", "-c",
       "fpath=(" + shell_quoted(std::filesystem::path(script).parent_path().string()) + " $fpath); autoload -Uz compinit; compinit -u -d " +
           shell_quoted(dir + "/zcompdump") + "; print -r -- ${_comps[hitl]}; autoload +X _hitl && whence -w _hitl"},
      30s);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("_hitl\n"), std::string::npos) << r.out << r.err;
  EXPECT_NE(r.out.find("_hitl: function"), std::string::npos) << r.out << r.err;
  const auto text = test::read_text(script);
  for (const char* part : {"_hitl_cmd_params_show()", "_hitl_cmd_fly_trajectory()", "--protocol-version=[MAVLink protocol version]:TEXT:(1.0 2.0)'",
                           "_files -g \"*.json\"", "(1.0 2.0)", "_hitl_messages", "HIL_ACTUATOR_CONTROLS", ":_hitl_faults", "names=(gps-loss"})
    EXPECT_NE(text.find(part), std::string::npos) << part;
}

}  // namespace
}  // namespace hitl
