// The doctor's link checks (engine/doctor/link_checks) on fixed inputs: HEARTBEAT and HIL mode, the
// MAVLink instances of PX4 and of hitl target, the actuator rate, flags and armed bit.
#include <gtest/gtest.h>

#include "base/mavlink/enums.h"
#include "engine/doctor/link_checks.h"
#include "tests/engine/doctor/check_fixtures.h"

namespace hitl::doctor {
namespace {

using namespace fixtures;

TEST(DoctorLink, HeartbeatAndHilMode) {
  auto none = heartbeat_check(Error{"no autopilot HEARTBEAT direct to 127.0.0.1:14558"}, std::nullopt);
  EXPECT_EQ(none.result, Verdict::Fail);
  EXPECT_TRUE(has(none.fix, "hitl target"));
  const auto hil = px4_heartbeat(mavlink::mode_flag::kCustomModeEnabled | mavlink::mode_flag::kHilEnabled);
  auto ok = heartbeat_check(std::string("through the session on 127.0.0.1:14600"), hil);
  EXPECT_EQ(ok.result, Verdict::Pass);
  EXPECT_TRUE(has(ok.saw, "PX4 system 1 through the session")) << ok.saw;
  EXPECT_TRUE(has(ok.saw, "1.0 Hz")) << ok.saw;
  EXPECT_EQ(hil_mode_check(hil).result, Verdict::Pass);
  auto no_hil = hil_mode_check(px4_heartbeat(mavlink::mode_flag::kCustomModeEnabled));
  EXPECT_EQ(no_hil.result, Verdict::Fail);
  EXPECT_TRUE(has(no_hil.fix, "SYS_HITL 1")) << no_hil.fix;
  EXPECT_EQ(hil_mode_check(std::nullopt).result, Verdict::Skip);
}

TEST(DoctorLink, MavlinkStatusOfPx4AndOfHitlTarget) {
  const std::string px4 =
      "\ninstance #0:\n\tGCS heartbeat valid\n\tmavlink chan: #0\n\ttype:\t\tGENERIC LINK OR RADIO\n"
      "\ttransport protocol: UDP (14560, remote port: 14561)\n\tBroadcast enabled: NO\n"
      "instance #1:\n\ttransport protocol: UDP (14556, remote port: 14557)\n"
      "instance #2:\n\ttransport protocol: UDP (14558, remote port: 14562)\n";
  const auto seen = parse_mavlink_status(px4);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_EQ(seen[0].udp_port, 14560);
  EXPECT_EQ(seen[0].remote, "14561");
  EXPECT_EQ(seen[2].udp_port, 14558);
  EXPECT_EQ(mavlink_instances_check(px4, 14560).result, Verdict::Pass);
  auto missing = mavlink_instances_check(px4, 14999);
  EXPECT_EQ(missing.result, Verdict::Fail);
  EXPECT_TRUE(has(missing.saw, "no instance on the HIL port UDP 14999")) << missing.saw;
  const std::string emulator =
      "instance #0 (HIL instance (--hil-port)):\n\tUDP (40000, remote port: none)\n\tpartner: none yet\n";
  EXPECT_EQ(mavlink_instances_check(emulator, 40000).result, Verdict::Pass);
  EXPECT_EQ(mavlink_instances_check(std::string("nsh: mavlink: command not found\n"), 14560).result, Verdict::Warn);
  EXPECT_EQ(mavlink_instances_check(Error{"timeout"}, 14560).result, Verdict::Warn);
}

TEST(DoctorLink, ActuatorRateAgainstLockstepOrTheBoardsStream) {
  EXPECT_DOUBLE_EQ(*expected_actuator_rate_hz(session(true, 5, 0, -1, -1)), 1250.0);
  EXPECT_DOUBLE_EQ(*expected_actuator_rate_hz(session(false, 1, 0, -1, -1)), 200.0);
  EXPECT_EQ(actuators_check(session(true, 5, 1240, 15, 0)).result, Verdict::Pass);
  EXPECT_EQ(actuators_check(session(false, 1, 199, 15, 0)).result, Verdict::Pass);
  EXPECT_EQ(actuators_check(session(false, 1, 140, 15, 0)).result, Verdict::Warn);
  EXPECT_EQ(actuators_check(session(false, 1, 50, 15, 0)).result, Verdict::Fail);
  auto none = actuators_check(session(true, 5, 0, -1, -1));
  EXPECT_EQ(none.result, Verdict::Fail);
  EXPECT_TRUE(has(none.saw, "none ever")) << none.saw;
  EXPECT_TRUE(has(none.fix, "HIL_ACTUATOR_CONTROLS -r 200")) << none.fix;
  EXPECT_EQ(actuators_check(SessionStatus{}).result, Verdict::Skip);
}

TEST(DoctorLink, FlagsAndArmedBit) {
  EXPECT_EQ(actuator_flags_check(session(true, 1, 250, 0x0F, 0)).result, Verdict::Pass);
  auto wrong = actuator_flags_check(session(true, 1, 250, 0x00, 0));
  EXPECT_EQ(wrong.result, Verdict::Fail);
  EXPECT_TRUE(has(wrong.saw, "flags 0x00")) << wrong.saw;
  EXPECT_EQ(actuator_flags_check(session(true, 1, 0, -1, -1)).result, Verdict::Skip);
  const auto disarmed = px4_heartbeat(mavlink::mode_flag::kHilEnabled);
  const auto armed = px4_heartbeat(mavlink::mode_flag::kHilEnabled | mavlink::mode_flag::kSafetyArmed);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 0), disarmed).result, Verdict::Pass);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 1), armed).result, Verdict::Pass);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 1), disarmed).result, Verdict::Fail);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, -1), disarmed).result, Verdict::Skip);
  EXPECT_EQ(armed_state_check(session(true, 1, 250, 15, 0), std::nullopt).result, Verdict::Skip);
}

}  // namespace
}  // namespace hitl::doctor
