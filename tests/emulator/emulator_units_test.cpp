#include <gtest/gtest.h>

#include "emulator/param_store.h"
#include "emulator/shell.h"

namespace hitl::target {
namespace {

std::string text_of(const std::vector<mavlink::msg::SerialControl>& replies) {
  std::string out;
  for (const auto& r : replies) {
    EXPECT_EQ(r.device, kSerialControlDevShell);
    EXPECT_EQ(r.flags, kSerialControlFlagReply);
    EXPECT_LE(r.count, 70);
    out.append(reinterpret_cast<const char*>(r.data.data()), r.count);
  }
  return out;
}

mavlink::msg::SerialControl input(const std::string& s) {
  mavlink::msg::SerialControl m;
  m.device = kSerialControlDevShell;
  m.count = static_cast<uint8_t>(s.size());
  std::copy(s.begin(), s.end(), m.data.begin());
  return m;
}

TEST(Shell, EchoesRunsTheLineAndReturnsThePrompt) {
  std::vector<std::string> ran;
  Shell shell([&](const std::string& line) {
    ran.push_back(line);
    return std::string(100, 'x') + "\n";  // longer than one reply
  });
  EXPECT_EQ(text_of(shell.on_serial_control(input("dsp_hi"))), "dsp_hi");
  const auto out = text_of(shell.on_serial_control(input("tl status\n")));
  ASSERT_EQ(ran.size(), 1u);
  EXPECT_EQ(ran[0], "dsp_hitl status");
  EXPECT_EQ(out, "tl status\n" + std::string(100, 'x') + "\n" + kShellPrompt);
  EXPECT_EQ(text_of(shell.on_serial_control(input("\n"))), std::string("\n") + kShellPrompt);  // empty line: prompt only
  auto other = input("x\n");
  other.device = 0;
  EXPECT_TRUE(shell.on_serial_control(other).empty());
}

TEST(Shell, ANonZeroReturnIsFollowedByPxhsFailureLine) {
  Shell shell([](const std::string& line) { return line.rfind("fail", 0) == 0 ? ShellResult{"Running: no\n", 1} : ShellResult{"ok\n"}; });
  EXPECT_EQ(text_of(shell.on_serial_control(input("fail now\n"))),
            "fail now\nRunning: no\nCommand 'fail' failed, returned 1.\n" + std::string(kShellPrompt));
  EXPECT_EQ(text_of(shell.on_serial_control(input("fine\n"))), "fine\nok\n" + std::string(kShellPrompt));
}

TEST(ParamStore, TypedSetsWithRanges) {
  ParamStore store;
  store.add("SYS_HITL", vehicle::ParamValue::int32(1), 0, 2);
  store.add("MPC_XY_P", vehicle::ParamValue::real32(0.95f), 0.0, 2.0);
  int changes = 0;
  store.on_change([&](const vehicle::Param&) { ++changes; });
  EXPECT_TRUE(store.set("MPC_XY_P", vehicle::ParamValue::real32(1.2f)).ok());
  EXPECT_EQ(*store.get("MPC_XY_P"), vehicle::ParamValue::real32(1.2f));
  EXPECT_FALSE(store.set("MPC_XY_P", vehicle::ParamValue::int32(1)).ok());    // wrong type
  EXPECT_FALSE(store.set("MPC_XY_P", vehicle::ParamValue::real32(5.0f)).ok());  // out of range
  EXPECT_FALSE(store.set("NOPE", vehicle::ParamValue::int32(1)).ok());
  EXPECT_EQ(changes, 1);
  EXPECT_EQ(store.index_of("MPC_XY_P"), 1u);
  EXPECT_EQ(store.at(0).name, "SYS_HITL");
}

}  // namespace
}  // namespace hitl::target
