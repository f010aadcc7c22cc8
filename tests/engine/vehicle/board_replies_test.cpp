// A board's answers to the parameter and shell protocols, collected and bounded (issue 19).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "engine/vehicle/board_replies.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;

msg::SerialControl reply(const std::string& text, uint8_t device = 10) {
  msg::SerialControl r;
  r.device = device;
  r.count = static_cast<uint8_t>(std::min<std::size_t>(text.size(), r.data.size()));
  std::memcpy(r.data.data(), text.data(), r.count);
  return r;
}

TEST(ShellOutput, PromptSplitAcrossRepliesEndsTheOutputAndIsStripped) {
  ShellOutput out;
  EXPECT_FALSE(out.append(reply("ls\nbin etc\npx")));
  EXPECT_FALSE(out.append(reply("nsh> ", 3)));  // another device: ignored
  EXPECT_TRUE(out.append(reply("h> ")));
  EXPECT_EQ(out.body(), "bin etc\n");
}

TEST(ShellOutput, ABoardThatNeverStopsTalkingIsCutAtTheBound) {
  ShellOutput out;
  const std::string chunk(70, 'x');
  for (std::size_t sent = 0; sent < 2 * kMaxShellOutputBytes; sent += chunk.size()) EXPECT_FALSE(out.append(reply(chunk)));
  EXPECT_EQ(out.text().size(), kMaxShellOutputBytes);
  EXPECT_TRUE(out.cut());
  EXPECT_TRUE(out.append(reply("pxh> ")));  // the prompt is still recognised past the bound
}

TEST(ParamCollector, KeepsTheFirstValueOfEachIndexBelowTheCount) {
  ParamCollector got;
  msg::ParamValue v;
  v.param_count = 2;
  std::strcpy(v.param_id.data(), "SYS_HITL");
  v.param_index = 0;
  EXPECT_FALSE(got.take(v));
  EXPECT_FALSE(got.take(v));  // a repeat
  v.param_index = 7;          // past the count: ignored
  EXPECT_FALSE(got.take(v));
  v.param_index = 1;
  std::strcpy(v.param_id.data(), "MAV_0_RATE");
  EXPECT_TRUE(got.take(v));
  ASSERT_EQ(got.params().size(), 2u);
  EXPECT_EQ(got.params()[1].name, "MAV_0_RATE");
}

}  // namespace
}  // namespace hitl::vehicle
