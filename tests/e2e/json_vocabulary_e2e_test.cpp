// One vocabulary for scripts (issue 18): with --json, a command prints {"type":"status",...} objects
// while it runs (and its items: frame, check) and exactly one {"type":"summary",...}, last.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/process.h"

namespace hitl {
namespace {

using namespace std::chrono_literals;

void follows_the_vocabulary(const std::vector<std::string>& args, bool expect_status = true) {
  std::vector<std::string> argv{test::hitl_binary(), "--json"};
  argv.insert(argv.end(), args.begin(), args.end());
  test::Process p(argv);
  p.wait(120s);
  const auto lines = p.out_lines();
  ASSERT_FALSE(lines.empty()) << args[0] << ": no JSON at all\n" << p.err();
  int summaries = 0, statuses = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto j = nlohmann::json::parse(lines[i], nullptr, false);
    ASSERT_TRUE(j.is_object() && j.contains("type")) << args[0] << ": not a typed JSON object: " << lines[i];
    const std::string type = j["type"];
    if (type == "summary") {
      ++summaries;
      EXPECT_EQ(i, lines.size() - 1) << args[0] << ": the summary is not last";
    } else if (type == "status") {
      ++statuses;
    } else {
      EXPECT_TRUE(type == "frame" || type == "check") << args[0] << ": type " << type;
    }
  }
  EXPECT_EQ(summaries, 1) << args[0];
  if (expect_status) {
    EXPECT_GT(statuses, 0) << args[0];
  }
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

}  // namespace
}  // namespace hitl
