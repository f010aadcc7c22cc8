// The small builders written once in engine/mavlink: every HEARTBEAT hitl sends (heartbeat.h), the
// fixed-size text fields (text_field.h) and MAV_SEVERITY <-> Severity (severity.h).
#include <gtest/gtest.h>

#include "base/mavlink/heartbeat.h"
#include "base/mavlink/severity.h"
#include "base/mavlink/text_field.h"

namespace hitl::mavlink {
namespace {

TEST(Heartbeat, EachRoleSaysWhatItIs) {
  const auto gcs = gcs_heartbeat();
  EXPECT_EQ(gcs.type, static_cast<uint8_t>(MavType::Gcs));
  EXPECT_EQ(gcs.autopilot, static_cast<uint8_t>(MavAutopilot::Invalid));
  EXPECT_EQ(gcs.system_status, static_cast<uint8_t>(MavState::Active));
  EXPECT_EQ(gcs.mavlink_version, kMavlinkVersion);

  EXPECT_EQ(simulator_heartbeat().type, static_cast<uint8_t>(MavType::Generic));
  EXPECT_EQ(simulator_heartbeat(MavState::Standby).system_status, static_cast<uint8_t>(MavState::Standby));
  EXPECT_EQ(onboard_heartbeat().type, static_cast<uint8_t>(MavType::Onboard));
  EXPECT_EQ(onboard_heartbeat().autopilot, static_cast<uint8_t>(MavAutopilot::Invalid));

  const auto px4 = px4_quadrotor_heartbeat(mode_flag::kSafetyArmed | mode_flag::kHilEnabled, 0x04030000, true);
  EXPECT_EQ(px4.type, static_cast<uint8_t>(MavType::Quadrotor));
  EXPECT_EQ(px4.autopilot, static_cast<uint8_t>(MavAutopilot::Px4));
  EXPECT_EQ(px4.base_mode, mode_flag::kSafetyArmed | mode_flag::kHilEnabled);
  EXPECT_EQ(px4.custom_mode, 0x04030000u);
  EXPECT_EQ(px4.system_status, static_cast<uint8_t>(MavState::Active));
  EXPECT_EQ(px4_quadrotor_heartbeat(0, 0, false).system_status, static_cast<uint8_t>(MavState::Standby));
  EXPECT_EQ(px4.mavlink_version, kMavlinkVersion);
}

TEST(TextField, ShortTextIsNulTerminatedAndFullTextHasNoNul) {
  std::array<char, 16> id;
  id.fill('x');
  set_text(id, "SYS_HITL");
  EXPECT_EQ(text_of(id), "SYS_HITL");
  EXPECT_EQ(id[8], '\0');
  EXPECT_EQ(id[15], '\0');  // the rest cleared
  set_text(id, "MPC_XY_VEL_P_ACC_LONGER");  // cut to the field
  EXPECT_EQ(text_of(id), "MPC_XY_VEL_P_ACC");
  set_text(id, "");
  EXPECT_EQ(text_of(id), "");
}

TEST(Severity, MavSeverityFoldsIntoFourOrderedLevelsAndBack) {
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Emergency)), Severity::Error);
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Critical)), Severity::Error);
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Error)), Severity::Error);
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Warning)), Severity::Warning);
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Notice)), Severity::Notice);
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Info)), Severity::Info);
  EXPECT_EQ(severity_of(static_cast<uint8_t>(MavSeverity::Debug)), Severity::Info);
  for (Severity s : {Severity::Info, Severity::Notice, Severity::Warning, Severity::Error})
    EXPECT_EQ(severity_of(static_cast<uint8_t>(mav_severity(s))), s) << to_string(s);
  EXPECT_EQ(worse(Severity::Warning, Severity::Notice), Severity::Warning);
  EXPECT_EQ(worse(Severity::Info, Severity::Error), Severity::Error);
}

}  // namespace
}  // namespace hitl::mavlink
