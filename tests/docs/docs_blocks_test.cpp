// The user's path is the tested path (issue 18): every shell block of README.md, docs/guide.md, docs/campaigns.md, docs/replay.md, docs/faults.md and docs/inspect.md.
// Each `hitl ... --option` in any block must exist in that command's --help (a renamed or removed
// flag fails here). Each block that needs no board runs, in the order written, from a clean
// directory (docs/ linked in), through the real binary (`hitl` on PATH is the built one), and must
// exit 0. A block that cannot run here has a marker before it, read and reported as the reason:
//   <!-- needs: board (on USB-Ethernet at 192.168.101.2) -->
// and a block may say what its output must contain (a line, a JSON field):
//   <!-- output: "end":"trajectory_done" -->
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <regex>

#include "tests/support/tools.h"

namespace hitl {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

struct Block {
  std::string where;  ///< "README.md:42", the line of its first command
  std::string file;
  int first_line = 0;
  std::string text;
  std::string needs;  ///< empty: runs here
  std::vector<std::string> outputs;
};

std::vector<Block> shell_blocks(const std::string& relative) {
  std::vector<Block> blocks;
  std::stringstream in(test::read_text(test::source_path(relative)));
  std::string line, needs;
  std::vector<std::string> outputs;
  const std::regex needs_marker(R"(^<!-- needs: (.*) -->\s*$)"), output_marker(R"(^<!-- output: (.*) -->\s*$)");
  std::optional<Block> open;
  for (int n = 1; std::getline(in, line); ++n) {
    std::smatch m;
    if (open) {
      if (line.rfind("```", 0) == 0) {
        blocks.push_back(*open);
        open.reset();
      } else {
        open->text += line + "\n";
      }
    } else if (std::regex_match(line, m, needs_marker)) {
      needs = m[1].str();
    } else if (std::regex_match(line, m, output_marker)) {
      outputs.push_back(m[1].str());
    } else if (line == "```sh") {
      open = Block{relative + ":" + std::to_string(n + 1), relative, n + 1, "", needs, outputs};
      needs.clear();
      outputs.clear();
    }
  }
  return blocks;
}

/// The words of a shell command line, quotes removed; a comment ends it.
std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  std::string word;
  char quote = 0;
  bool in_word = false;
  for (char c : line) {
    if (quote) {
      if (c == quote) quote = 0;
      else word += c;
      continue;
    }
    if (c == '"' || c == '\'') {
      quote = c;
      in_word = true;
    } else if (c == '#' && !in_word) {
      break;
    } else if (c == ' ' || c == '\t') {
      if (in_word) out.push_back(word);
      word.clear();
      in_word = false;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) out.push_back(word);
  return out;
}

class HelpCache {
 public:
  /// `hitl ARGS --help`, or nullopt when hitl refuses ARGS.
  std::optional<std::string> help(const std::vector<std::string>& args) {
    std::string key;
    for (const auto& a : args) key += a + " ";
    if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    std::vector<std::string> argv = args;
    argv.push_back("--help");
    const auto r = test::run_hitl(argv, 20s);
    std::optional<std::string> text;
    if (r.exit_code == 0) text = r.out;
    cache_[key] = text;
    return text;
  }

 private:
  std::map<std::string, std::optional<std::string>> cache_;
};

/// The options of one `hitl ...` command that its --help (or the global help) does not list.
std::vector<std::string> unknown_options(const std::vector<std::string>& cmd, HelpCache& helps) {
  std::vector<std::string> path;  // subcommand words
  std::vector<std::string> options;
  for (std::size_t i = 1; i < cmd.size(); ++i) {
    const std::string& w = cmd[i];
    if (w.rfind("--", 0) == 0 && w.size() > 2) {
      options.push_back(w.substr(0, w.find('=')));
    } else if (w[0] != '-' && (path.empty() || (options.empty() && path.size() < 2))) {
      std::vector<std::string> longer = path;
      longer.push_back(w);
      if (helps.help(longer)) path = longer;
    }
  }
  const std::string global = helps.help({}).value_or("");
  const std::string own = helps.help(path).value_or("");
  std::vector<std::string> missing;
  for (const auto& o : options) {
    const std::regex listed("(^|[\\s,])" + o + "([\\s,=\\[]|$)");
    if (!std::regex_search(own, listed) && !std::regex_search(global, listed)) missing.push_back(o);
  }
  return missing;
}

TEST(DocsBlocks, EveryDocumentedOptionExists) {
  HelpCache helps;
  int commands = 0;
  for (const char* doc : {"README.md", "docs/guide.md", "docs/campaigns.md", "docs/replay.md", "docs/faults.md", "docs/inspect.md"}) {
    for (const auto& block : shell_blocks(doc)) {
      std::stringstream lines(block.text);
      int line_no = block.first_line - 1;
      for (std::string line; std::getline(lines, line);) {
        ++line_no;
        // Each command of a pipeline or list on its own.
        const auto all = words(line);
        std::vector<std::string> cmd;
        auto check = [&] {
          if (!cmd.empty() && fs::path(cmd[0]).filename() == "hitl") {
            ++commands;
            for (const auto& o : unknown_options(cmd, helps))
              ADD_FAILURE() << block.file << ":" << line_no << ": `" << line << "`: " << o << " is not an option of this command any more";
          }
          cmd.clear();
        };
        for (const auto& w : all) {
          if (w == "&&" || w == "||" || w == "|" || w == ";" || w == "&") check();
          else cmd.push_back(w);
        }
        check();
      }
    }
  }
  EXPECT_GT(commands, 30);
}

/// Runs the blocks of `doc` that need nothing this machine lacks, in order, in one clean directory.
void run_blocks(const std::string& doc) {
  const auto dir = test::temp_dir() + "/user";
  fs::create_directories(dir);
  fs::create_directory_symlink(test::source_path("docs"), dir + "/docs");
  const std::string path = fs::path(test::hitl_binary()).parent_path().string() + ":" + (std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin:/bin");
  int ran = 0;
  for (const auto& block : shell_blocks(doc)) {
    if (!block.needs.empty()) {
      std::cout << "[ skipped  ] " << block.where << ": needs " << block.needs << std::endl;
      continue;
    }
    ++ran;
    // Whatever the block left running is stopped when it ends, failed or not.
    const std::string script = "trap 'kill $(jobs -p) 2>/dev/null || true' EXIT\n" + block.text;
    test::Process p({"/usr/bin/env", "PATH=" + path, "/bin/bash", "-c", "cd \"$0\" && set -euo pipefail && eval \"$1\"", dir, script});
    const int code = p.wait(240s);
    EXPECT_EQ(code, 0) << block.where << " failed (exit " << code << "):\n" << block.text << "--- stdout\n" << p.out()
                       << "--- stderr\n" << p.err();
    for (const auto& expected : block.outputs)
      EXPECT_NE(p.out().find(expected), std::string::npos) << block.where << ": the output no longer has " << expected << "\n"
                                                           << p.out();
    std::cout << "[ ran      ] " << block.where << " (exit " << code << ")" << std::endl;
  }
  EXPECT_GT(ran, 0) << doc << " has no block that runs without a board";
}

TEST(DocsBlocks, ReadmeRunsAsWritten) { run_blocks("README.md"); }
TEST(DocsBlocks, GuideRunsAsWritten) { run_blocks("docs/guide.md"); }
TEST(DocsBlocks, ReplayRunsAsWritten) { run_blocks("docs/replay.md"); }
TEST(DocsBlocks, FaultsRunAsWritten) { run_blocks("docs/faults.md"); }
TEST(DocsBlocks, CampaignsRunAsWritten) { run_blocks("docs/campaigns.md"); }
TEST(DocsBlocks, InspectRunsAsWritten) { run_blocks("docs/inspect.md"); }

}  // namespace
}  // namespace hitl
