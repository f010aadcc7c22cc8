// One vocabulary for scripts (issue 18): with --json, a command prints {"type":"status",...} objects
// while it runs (and its items: frame, check) and exactly one {"type":"summary",...}, last.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

/// The summary, for the checks a test adds.
nlohmann::json follows_the_vocabulary(const std::vector<std::string>& args, bool expect_status = true) {
  std::vector<std::string> argv{test::hitl_binary(), "--json"};
  argv.insert(argv.end(), args.begin(), args.end());
  test::Process p(argv);
  p.wait(120s);
  const auto lines = p.out_lines();
  EXPECT_FALSE(lines.empty()) << args[0] << ": no JSON at all\n" << p.err();
  int summaries = 0, statuses = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto j = nlohmann::json::parse(lines[i], nullptr, false);
    EXPECT_TRUE(j.is_object() && j.contains("type")) << args[0] << ": not a typed JSON object: " << lines[i];
    if (!j.is_object() || !j.contains("type")) continue;
    const std::string type = j["type"];
    if (type == "summary") {
      ++summaries;
      EXPECT_EQ(i, lines.size() - 1) << args[0] << ": the summary is not last";
    } else if (type == "status") {
      ++statuses;
    } else {
      EXPECT_TRUE(type == "frame" || type == "check" || type == "shell") << args[0] << ": type " << type;
    }
  }
  EXPECT_EQ(summaries, 1) << args[0];
  if (expect_status) {
    EXPECT_GT(statuses, 0) << args[0];
  }
  return lines.empty() ? nlohmann::json() : nlohmann::json::parse(lines.back(), nullptr, false);
}

std::string port() { return std::to_string(test::free_udp_port()); }

TEST(JsonVocabulary, Sim) {
  follows_the_vocabulary({"sim", "-i", "127.0.0.1", "--hil-port", port(), "--local-port", port(), "--no-vio", "--clients", "0",
                          "--duration", "2", "--speed", "1"});
}
TEST(JsonVocabulary, Inspect) { follows_the_vocabulary({"inspect", "--port", port(), "--duration", "2"}); }
TEST(JsonVocabulary, Bridge) {
  follows_the_vocabulary({"bridge", "-i", "127.0.0.1", "--port", port(), "--local-port", port(), "--clients", "0", "--duration", "2"});
}
TEST(JsonVocabulary, Target) {
  follows_the_vocabulary({"target", "--bind", "127.0.0.1", "--hil-port", port(), "--gcs-port", port(), "--vio-port", "0",
                          "--duration", "2"});
}
TEST(JsonVocabulary, Demo) { follows_the_vocabulary({"demo", "--speed", "20"}); }  // a few seconds: status objects too

/// The board-operating commands against `hitl target`: params and shell too (issue 18 point 6).
class JsonVocabularyBoard : public ::testing::Test {
 protected:
  void SetUp() override {
    gcs_ = port();
    board_ = std::make_unique<test::Process>(std::vector<std::string>{
        test::hitl_binary(), "target", "--bind", "127.0.0.1", "--hil-port", port(), "--gcs-port", gcs_, "--vio-port", "0"});
    ASSERT_TRUE(board_->wait_for_stderr("EMULATED", 10s)) << board_->err();
  }
  void TearDown() override {
    board_->signal(SIGINT);
    board_->wait(10s);
  }
  /// `command` ARGS... with the link to the board (one local port: the board answers the first it heard).
  std::vector<std::string> to_board(std::vector<std::string> args) {
    args.insert(args.end(), {"-i", "127.0.0.1", "--port", gcs_, "--local-port", local_, "--session-port", port()});
    return args;
  }
  std::string gcs_, local_ = port();
  std::unique_ptr<test::Process> board_;
};

TEST_F(JsonVocabularyBoard, Params) {
  for (const auto& action : std::vector<std::vector<std::string>>{{"get", "SYS_HITL"}, {"set", "SYS_HITL", "1"}, {"show", "CAL_*"},
                                                                   {"check"}, {"diff"}, {"reset", "--dry-run"}}) {
    std::vector<std::string> args{"params"};
    args.insert(args.end(), action.begin(), action.end());
    const auto summary = follows_the_vocabulary(to_board(args), false);
    EXPECT_EQ(summary["command"], "params") << action[0];
    EXPECT_EQ(summary["action"], action[0]);
  }
  // Ending on an error: still exactly one summary, with the reason.
  const auto failed = follows_the_vocabulary(to_board({"params", "get", "SYS_HITLL"}), false);
  EXPECT_FALSE(failed["ok"].get<bool>());
  EXPECT_NE(failed["error"].get<std::string>().find("did you mean 'SYS_HITL'?"), std::string::npos) << failed;
}

TEST_F(JsonVocabularyBoard, Shell) {
  const auto one = follows_the_vocabulary(to_board({"shell", "-c", "ver all"}), false);
  EXPECT_EQ(one["command"], "shell");
  EXPECT_EQ(one["commands"], 1);
  EXPECT_TRUE(one["ok"].get<bool>());
  const auto failed = follows_the_vocabulary(to_board({"shell", "-c", "no_such_command"}), false);
  EXPECT_EQ(failed["failed"], 1);
  EXPECT_FALSE(failed["ok"].get<bool>());
}

}  // namespace
}  // namespace hitl
