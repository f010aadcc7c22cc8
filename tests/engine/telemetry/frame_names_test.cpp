// `hitl inspect --show` prints names, not numbers (issue 18 point 9): enum and bitmask values from
// enums.h, PX4's custom_mode as the dashboard names it; values hitl has no name for stay numbers.
#include <gtest/gtest.h>

#include "base/mavlink/enums.h"
#include "base/mavlink/message_set.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"
#include "engine/inspect/frame_text.h"
#include "engine/mavlink/enum_names.h"
#include "engine/mavlink/field_format.h"

namespace hitl {
namespace {

using namespace mavlink;

template <class M>
Frame frame_of(const M& message, const MessageSet& set) {
  Frame f;
  f.msgid = M::kId;
  f.payload_len = M::kMaxLength;
  encode_payload(message, f.payload.data());
  f.desc = set.find(M::kId);
  return f;
}

TEST(EnumNames, PlainEnumsByNameAndUnknownValuesAsNothing) {
  EXPECT_EQ(enum_value_name("MAV_TYPE", 2), "QUADROTOR");
  EXPECT_EQ(enum_value_name("MAV_AUTOPILOT", 12), "PX4");
  EXPECT_EQ(enum_value_name("MAV_STATE", 4), "ACTIVE");
  EXPECT_EQ(enum_value_name("MAV_RESULT", 1), "TEMPORARILY_REJECTED");
  EXPECT_EQ(enum_value_name("MAV_SEVERITY", 4), "WARNING");
  EXPECT_EQ(enum_value_name("MAV_CMD", 400), "COMPONENT_ARM_DISARM");
  EXPECT_FALSE(enum_value_name("MAV_TYPE", 77));         // a value enums.h does not hold
  EXPECT_FALSE(enum_value_name("MAV_BATTERY_TYPE", 1));  // an enum hitl has no names for
}

TEST(EnumNames, BitmasksJoinTheSetBitsAndKeepUnnamedOnesInHex) {
  EXPECT_EQ(enum_value_name("MAV_MODE_FLAG", mode_flag::kCustomModeEnabled | mode_flag::kSafetyArmed),
            "CUSTOM_MODE_ENABLED|SAFETY_ARMED");
  EXPECT_EQ(enum_value_name("MAV_MODE_FLAG", 0), "0");
  EXPECT_EQ(enum_value_name("MAV_SYS_STATUS_SENSOR", sys_status::kGyro | 0x400), "3D_GYRO|0x400");
}

TEST(FrameText, HeartbeatSaysTypeAutopilotModeFlagsStateAndPx4Mode) {
  const auto set = MessageSet::compiled();
  msg::Heartbeat hb;
  hb.type = 2;
  hb.autopilot = 12;
  hb.base_mode = mode_flag::kCustomModeEnabled | mode_flag::kSafetyArmed;
  hb.custom_mode = (4u << 16) | (3u << 24);  // AUTO / LOITER
  hb.system_status = 4;
  hb.mavlink_version = 3;
  EXPECT_EQ(inspect::frame_text(frame_of(hb, set)),
            "HEARTBEAT custom_mode=Hold type=QUADROTOR autopilot=PX4 base_mode=CUSTOM_MODE_ENABLED|SAFETY_ARMED "
            "system_status=ACTIVE mavlink_version=3");
  hb.custom_mode = (4u << 16) | (9u << 24);  // a name with a space is quoted
  EXPECT_NE(inspect::frame_text(frame_of(hb, set)).find("custom_mode=\"Precision Land\""), std::string::npos);
  hb.autopilot = 3;  // not PX4: custom_mode is that autopilot's own word, and 3 is no name hitl holds
  const auto other = inspect::frame_text(frame_of(hb, set));
  EXPECT_NE(other.find("custom_mode=" + std::to_string(hb.custom_mode) + " "), std::string::npos) << other;
  EXPECT_NE(other.find("autopilot=3 "), std::string::npos) << other;
}

TEST(FrameText, CommandAckAndStatustextByName) {
  const auto set = MessageSet::compiled();
  msg::CommandAck ack;
  ack.command = 400;
  ack.result = 2;
  const auto ack_text = inspect::frame_text(frame_of(ack, set));
  EXPECT_NE(ack_text.find("command=COMPONENT_ARM_DISARM"), std::string::npos) << ack_text;
  EXPECT_NE(ack_text.find("result=DENIED"), std::string::npos) << ack_text;
  msg::Statustext st;
  st.severity = 4;
  const std::string text = "Preflight Fail: GPS";
  std::copy(text.begin(), text.end(), st.text.begin());
  const auto st_text = format_message(frame_of(st, set));
  EXPECT_NE(st_text.find("severity=WARNING text=\"Preflight Fail: GPS\""), std::string::npos) << st_text;
  EXPECT_EQ(st_text.find('\n'), std::string::npos);  // one line per message
}

}  // namespace
}  // namespace hitl
