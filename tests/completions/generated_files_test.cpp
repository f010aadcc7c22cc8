// The committed files generated from hitl's command-line model (completions/, docs/hitl.1,
// docs/config.md) are what the built binary generates now; the man page renders without a
// warning from groff, mandoc or man.
#include <gtest/gtest.h>

#include <regex>

#include "tests/support/tools.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

struct Generated {
  const char* file;
  std::vector<std::string> args;
};

const std::vector<Generated>& generated_files() {
  static const std::vector<Generated> files{{"completions/hitl.bash", {"completion", "bash"}},
                                            {"completions/_hitl", {"completion", "zsh"}},
                                            {"completions/hitl.fish", {"completion", "fish"}},
                                            {"docs/hitl.1", {"reference", "man"}},
                                            {"docs/config.md", {"reference", "config"}}};
  return files;
}

/// "line N: committed '...', generated '...'" for the first difference.
std::string first_difference(const std::string& committed, const std::string& generated) {
  const auto a = test::lines_of(committed), b = test::lines_of(generated);
  for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    const std::string x = i < a.size() ? a[i] : "(end of file)", y = i < b.size() ? b[i] : "(end of file)";
    if (x != y) return "first difference near line " + std::to_string(i + 1) + ":\n  committed: " + x + "\n  generated: " + y;
  }
  return "they differ in blank lines only";
}

TEST(GeneratedFiles, CommittedFilesMatchWhatTheBinaryGenerates) {
  for (const auto& g : generated_files()) {
    const auto r = test::run_hitl(g.args);
    ASSERT_EQ(r.exit_code, 0) << "hitl " << g.args[0] << " " << g.args[1] << ": " << r.err;
    ASSERT_FALSE(r.out.empty());
    const auto committed = test::read_text(test::source_path(g.file));
    EXPECT_TRUE(committed == r.out) << g.file
                                    << " is out of date with hitl's command-line model. Regenerate it with "
                                       "scripts/regen-completions.sh (or: cmake --build BUILD_DIR --target "
                                       "regen-completions) and commit the result; "
                                    << first_difference(committed, r.out);
  }
}

TEST(GeneratedFiles, EveryVisibleCommandIsInTheManPageAndNoHiddenOne) {
  const auto page = test::read_text(test::source_path("docs/hitl.1"));
  const auto help = test::run_hitl({"--help"});
  ASSERT_EQ(help.exit_code, 0);
  // The subcommands as --help lists them: "  name   description" lines after "Subcommands:".
  const auto at = help.out.find("Subcommands:");
  ASSERT_NE(at, std::string::npos) << help.out;
  int listed = 0;
  for (const auto& line : test::lines_of(help.out.substr(at))) {
    if (line.size() < 3 || line.rfind("  ", 0) != 0 || line[2] == ' ') continue;
    const auto name = line.substr(2, line.find(' ', 2) - 2);
    EXPECT_NE(page.find(".SS \"hitl " + name), std::string::npos) << name;
    ++listed;
  }
  EXPECT_GE(listed, 8);
  EXPECT_EQ(page.find(".SS \"hitl reference"), std::string::npos);  // hidden
}

TEST(ManPage, GroffRendersItWithoutAWarning) {
  if (test::find_program("groff").empty()) GTEST_SKIP() << "groff is not installed (scripts/install-deps.sh --test)";
  const auto r = test::run_program({"groff", "-man", "-Tutf8", "-ww", "-z", test::source_path("docs/hitl.1")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST(ManPage, MandocLintsItWithoutAWarning) {
  if (test::find_program("mandoc").empty()) GTEST_SKIP() << "mandoc is not installed (scripts/install-deps.sh --test)";
  const auto r = test::run_program({"mandoc", "-T", "lint", "-W", "warning", test::source_path("docs/hitl.1")});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out + r.err, "");
}

TEST(ManPage, ManShowsEveryCommandAsText) {
  if (test::find_program("man").empty()) GTEST_SKIP() << "man is not installed (scripts/install-deps.sh --test)";
  const auto r = test::run_program({"/usr/bin/env", "MANWIDTH=100", "MAN_DISABLE_SECCOMP=1", "man", "-l",
                                    test::source_path("docs/hitl.1")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const char* text : {"hitl sim [OPTIONS]", "hitl params show [OPTIONS] [PATTERN]", "--protocol-version 1.0|2.0",
                           "Default: 14560.", "hitl inspect --port 14570 --duration 5 --expect ODOMETRY=250",
                           "EXIT STATUS", "CONFIGURATION FILE"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << " not in:\n" << r.out.substr(0, 3000);
  EXPECT_EQ(r.out.find("\\f"), std::string::npos);  // no escape left unrendered
  EXPECT_FALSE(std::regex_search(r.out, std::regex("@[A-Z_]+@")));  // no @PLACEHOLDER@ left (an @ in text is fine: --fault NAME@T)
}

TEST(ConfigReference, HasASectionPerCommandWithOptions) {
  const auto md = test::read_text(test::source_path("docs/config.md"));
  for (const char* section : {"## Global options", "## `[sim]`: `hitl sim`", "## `[inspect]`: `hitl inspect`",
                              "## `[params]`: `hitl params`", "## `[target]`: `hitl target`"})
    EXPECT_NE(md.find(section), std::string::npos) << section;
  EXPECT_NE(md.find("| `target-ip` (`mavlink-addr`, flag `-i`) |"), std::string::npos);
  EXPECT_NE(md.find("| `hil-port` (`mavlink-udp-remote-port`) | integer: 1 to 65535 | `14560` |"), std::string::npos);
}

}  // namespace
}  // namespace hitl
