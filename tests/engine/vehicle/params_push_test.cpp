// push_params against a scripted board on loopback: what differs is set and read back, what
// matches is left alone, a value the board will not take fails with what it read back, a missing
// parameter fails or (absent_ok) is absent with its note, and a dry run sends no PARAM_SET.
#include "engine/vehicle/params_push.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <map>
#include <mutex>
#include <string>

#include "base/mavlink/messages.h"
#include "tests/support/board_link.h"
#include "tests/support/scripted_board.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
using test::connect_to;
using test::ScriptedBoard;

std::string param_name(const std::array<char, 16>& id) { return std::string(id.data(), strnlen(id.data(), id.size())); }

/// A board with REAL32 parameters; STUCK keeps its value whatever is set.
struct ParamBoard {
  std::mutex mutex;
  std::map<std::string, float> values = {{"A", 1.0F}, {"B", 2.0F}, {"STUCK", 3.0F}};
  std::atomic<int> sets{0};

  void answer(const std::string& name, test::MavlinkPeer& peer) {
    std::lock_guard lock(mutex);
    const auto it = values.find(name);
    if (it == values.end()) return;
    msg::ParamValue v;
    std::memcpy(v.param_id.data(), name.data(), name.size());
    v.param_value = it->second;
    v.param_type = 9;  // MAV_PARAM_TYPE_REAL32
    v.param_count = static_cast<uint16_t>(values.size());
    v.param_index = static_cast<uint16_t>(std::distance(values.begin(), it));
    peer.send(v);
  }
  ScriptedBoard::Script script() {
    return [this](const mavlink::Frame& f, test::MavlinkPeer& peer) {
      if (f.is<msg::ParamSet>()) {
        const auto s = f.as<msg::ParamSet>();
        const std::string name = param_name(s.param_id);
        ++sets;
        {
          std::lock_guard lock(mutex);
          if (values.count(name) && name != "STUCK") values[name] = s.param_value;
        }
        answer(name, peer);
      } else if (f.is<msg::ParamRequestRead>()) {
        answer(param_name(f.as<msg::ParamRequestRead>().param_id), peer);
      }
    };
  }
  std::vector<Param> download() {
    std::lock_guard lock(mutex);
    std::vector<Param> all;
    for (const auto& [name, value] : values) all.push_back({name, ParamValue::real32(value)});
    return all;
  }
};

TEST(ParamsPush, SetsWhatDiffersVerifiesItAndLeavesTheRest) {
  ParamBoard params;
  ScriptedBoard board(params.script());
  auto link = connect_to(board.port());
  ParamClient client(*link);
  const std::vector<Param> wanted = {{"A", ParamValue::real32(1.0F)}, {"B", ParamValue::real32(5.0F)},
                                     {"STUCK", ParamValue::real32(9.0F)}, {"NOPE", ParamValue::real32(1.0F)}};
  const auto r = push_params(client, *link, params.download(), wanted, {});
  ASSERT_EQ(r.set.size(), 1U);
  EXPECT_EQ(r.set[0].name, "B");
  EXPECT_EQ(r.set[0].from, ParamValue::real32(2.0F));
  EXPECT_EQ(r.set[0].to, ParamValue::real32(5.0F));
  EXPECT_EQ(r.unchanged, std::vector<std::string>{"A"});
  ASSERT_EQ(r.failed.size(), 2U);
  EXPECT_EQ(r.failed[0].name, "STUCK");
  EXPECT_NE(r.failed[0].error.find("kept 3"), std::string::npos) << r.failed[0].error;  // the client says what the board kept
  EXPECT_EQ(r.failed[1].name, "NOPE");
  EXPECT_EQ(r.failed[1].error, "the board has no such parameter");
  EXPECT_TRUE(r.absent.empty());
  EXPECT_FALSE(r.ok(false));
  std::lock_guard lock(params.mutex);
  EXPECT_EQ(params.values["B"], 5.0F);
}

TEST(ParamsPush, AnAbsentParameterOfTheHitlSetIsNotedAndFailsOnlyWhenStrict) {
  ParamBoard params;
  ScriptedBoard board(params.script());
  auto link = connect_to(board.port());
  ParamClient client(*link);
  const std::vector<Param> wanted = {{"A", ParamValue::real32(1.0F)}, {"COM_ARM_EKF_POS", ParamValue::real32(0.5F)}};
  const auto r = push_params(client, *link, params.download(), wanted, {.dry_run = false, .absent_ok = true});
  ASSERT_EQ(r.absent.size(), 1U);
  EXPECT_EQ(r.absent[0].name, "COM_ARM_EKF_POS");
  ASSERT_NE(r.absent[0].note, nullptr);  // hitl-defaults.params notes it as absent in PX4 v1.16
  EXPECT_FALSE(r.firmware.has_value());   // this board does not answer AUTOPILOT_VERSION
  EXPECT_TRUE(r.failed.empty());
  EXPECT_TRUE(r.ok(false));
  EXPECT_FALSE(r.ok(true));
}

TEST(ParamsPush, ADryRunPlansWithoutSetting) {
  ParamBoard params;
  ScriptedBoard board(params.script());
  auto link = connect_to(board.port());
  ParamClient client(*link);
  const auto r = push_params(client, *link, params.download(), {{"B", ParamValue::real32(7.0F)}}, {.dry_run = true});
  ASSERT_EQ(r.set.size(), 1U);
  EXPECT_EQ(r.set[0].to, ParamValue::real32(7.0F));
  EXPECT_EQ(params.sets.load(), 0);
  std::lock_guard lock(params.mutex);
  EXPECT_EQ(params.values["B"], 2.0F);
}

}  // namespace
}  // namespace hitl::vehicle
