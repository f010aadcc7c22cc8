// A board for the plan tests: answers commands from a table (by prefix), records every command and
// push, and fails the one it is told to.
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "engine/board/board_shell.h"

namespace hitl::board::test {

class ScriptedShell : public BoardShell {
 public:
  std::map<std::string, net::ProgramOutput> answers;  ///< command prefix -> answer (default: exit 0, no output)
  std::string fail_prefix;                            ///< a command starting with it exits 1
  std::vector<std::string> log;                       ///< "$ CMD" or "push LOCAL-CONTENT -> REMOTE"
  std::map<std::string, std::string> pushed;          ///< remote -> content

  Expected<net::ProgramOutput> run(const std::string& command) override {
    log.push_back("$ " + command);
    if (!fail_prefix.empty() && command.rfind(fail_prefix, 0) == 0) return net::ProgramOutput{1, "", "dpkg: error: the board says no\n"};
    for (const auto& [prefix, answer] : answers)
      if (command.rfind(prefix, 0) == 0) return answer;
    return net::ProgramOutput{0, "", ""};
  }
  Status push(const std::string& local, const std::string& remote) override {
    std::ifstream in(local);
    std::stringstream ss;
    ss << in.rdbuf();
    pushed[remote] = ss.str();
    log.push_back("push -> " + remote);
    return Ok{};
  }
  std::string describe() const override { return "scripted board"; }
};

}  // namespace hitl::board::test
