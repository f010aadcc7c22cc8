// Every number option of every command refuses nan and inf with a plain line and exit 2 (issue 19:
// --actuator-timeout nan disabled the motor-stop failsafe; --lockstep-timeout nan was taken). The
// options are read from each command's --help, so an option added later is covered without
// touching this test.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

/// The subcommand names listed under "Subcommands:" in a --help text.
std::vector<std::string> subcommands(const std::string& help) {
  std::vector<std::string> out;
  const auto at = help.find("Subcommands:");
  if (at == std::string::npos) return out;
  std::istringstream in(help.substr(at));
  std::string line;
  std::getline(in, line);
  static const std::regex row(R"(^  ([a-z][a-z-]*)\s)");
  std::smatch m;
  while (std::getline(in, line) && !line.empty())
    if (std::regex_search(line, m, row)) out.push_back(m[1]);
  return out;
}

struct NumberOption {
  std::vector<std::string> command;
  std::string name;
  bool floating;
};

/// Options whose --help says they take a number: "Accepts a number" (floating) or "Accepts an
/// integer", in the notes after the description (wrapped over the option's lines).
std::vector<NumberOption> number_options(const std::vector<std::string>& command, const std::string& help) {
  std::vector<NumberOption> out;
  std::vector<std::string> blocks;  // an option's lines, joined
  std::istringstream in(help);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("  -", 0) == 0) blocks.push_back(line);
    else if (!blocks.empty() && line.rfind("    ", 0) == 0) blocks.back() += " " + line;
    else if (line.rfind("  ", 0) != 0) blocks.emplace_back();  // a heading or a blank line ends an option
  }
  static const std::regex name(R"(^  (?:-\w, )?(--[a-z][a-z0-9-]*))");
  static const std::regex accepts(R"(Accepts\s+(a\s+number|an\s+integer))");
  std::smatch n, a;
  for (const auto& b : blocks)
    if (std::regex_search(b, n, name) && std::regex_search(b, a, accepts))
      out.push_back({command, n[1], a[1].str().find("number") != std::string::npos});
  return out;
}

TEST(NumberOptions, EveryCommandRefusesNanAndInfPlainly) {
  std::vector<NumberOption> all;
  const auto top = test::run_hitl({"--help"}, 20s);
  for (const auto& cmd : subcommands(top.out)) {
    const auto help = test::run_hitl({cmd, "--help"}, 20s).out;
    auto found = number_options({cmd}, help);
    all.insert(all.end(), found.begin(), found.end());
    for (const auto& sub : subcommands(help)) {
      found = number_options({cmd, sub}, test::run_hitl({cmd, sub, "--help"}, 20s).out);
      all.insert(all.end(), found.begin(), found.end());
    }
  }
  ASSERT_GT(all.size(), 30u);  // sim alone has a dozen
  int floating = 0;
  for (const auto& o : all) {
    for (const char* bad : {"nan", "inf", "-inf"}) {
      std::vector<std::string> args = o.command;
      args.push_back(o.name + "=" + bad);  // "=": "-inf" must not read as an option
      const auto r = test::run_hitl(args, 15s);
      const std::string what = args[0] + " " + o.name + " " + bad;
      EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
      EXPECT_NE(r.err.find(o.name), std::string::npos) << what << "\n" << r.err;
      EXPECT_EQ(r.err.find("17976931348623157"), std::string::npos) << what << "\n" << r.err;  // no DBL_MAX in digits
      if (o.floating) {
        EXPECT_NE(r.err.find(std::string(bad) + " is not a finite number"), std::string::npos) << what << "\n" << r.err;
      }
    }
    floating += o.floating ? 1 : 0;
  }
  EXPECT_GT(floating, 15);
}

}  // namespace
}  // namespace hitl
