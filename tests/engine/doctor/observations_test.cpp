// What the doctor reads off the link (engine/doctor/observations): the autopilot's HEARTBEAT and the
// session's status, from frames.
#include <gtest/gtest.h>

#include "base/contract/session_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_encoder.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "engine/doctor/observations.h"

namespace hitl::doctor {
namespace {

TEST(DoctorObservations, AutopilotAndSessionStatusFromFrames) {
  static const auto messages = mavlink::MessageSet::compiled();
  mavlink::FrameParser parser(messages);
  ObservationTracker tracker;
  auto feed = [&](auto message, uint8_t sysid, bool autopilot, double t_s) {
    mavlink::FrameEncoder enc(sysid, 1);
    mavlink::FrameBuffer buf;
    const auto n = enc.encode(message, buf);
    parser.parse_datagram({buf.data(), n}, [&](const mavlink::Frame& f) {
      if (autopilot) tracker.on_autopilot_frame(f, t_s);
      else tracker.on_other_frame(f, t_s);
    });
  };
  mavlink::msg::Heartbeat hb;
  hb.autopilot = 12;
  hb.base_mode = mavlink::mode_flag::kHilEnabled | mavlink::mode_flag::kSafetyArmed;
  feed(hb, 1, true, 1.0);
  feed(hb, 1, true, 2.0);
  auto named_float = [](std::string_view name, float v) {
    mavlink::msg::NamedValueFloat m;
    std::copy(name.begin(), name.end(), m.name.begin());
    m.value = v;
    return m;
  };
  auto named_int = [](std::string_view name, int32_t v) {
    mavlink::msg::NamedValueInt m;
    std::copy(name.begin(), name.end(), m.name.begin());
    m.value = v;
    return m;
  };
  feed(named_int(hitl::kStatusLateName, 4), 250, false, 1.0);  // before sim_rtf: not yet known as the session
  feed(named_float(hitl::kStatusRtfName, 4.9f), 250, false, 1.0);
  feed(named_int(hitl::kStatusLateName, 5), 250, false, 1.0);
  feed(named_float(hitl::kStatusSpeedName, 5.0f), 250, false, 1.0);
  feed(named_int(hitl::kStatusLockstepName, 1), 250, false, 1.0);
  feed(named_float(hitl::kStatusActuatorRateName, 1230.0f), 250, false, 1.0);
  feed(named_int(hitl::kStatusActuatorFlagsName, 15), 250, false, 1.0);
  feed(named_int(hitl::kStatusActuatorArmedName, 1), 250, false, 1.0);
  feed(named_int(hitl::kStatusPauseName, 0), 250, false, 1.0);
  feed(named_int(hitl::kStatusActuatorFlagsName, 0), 77, false, 1.5);  // another system: ignored
  feed(named_float(hitl::kStatusRtfName, 5.0f), 250, false, 2.0);
  feed(named_int(hitl::kStatusLateName, 9), 250, false, 2.0);
  mavlink::msg::Statustext st;
  const std::string text = "Preflight Fail: ekf2 not aligned";
  std::copy(text.begin(), text.end(), st.text.begin());
  feed(st, 1, true, 2.0);
  const auto& seen = tracker.observations();
  ASSERT_TRUE(seen.heartbeat);
  EXPECT_EQ(seen.heartbeat->count, 2u);
  EXPECT_TRUE(seen.heartbeat->armed());
  const auto& s = seen.session;
  EXPECT_TRUE(s.heard());
  EXPECT_EQ(s.reports, 2u);
  EXPECT_EQ(*s.sysid, 250);
  EXPECT_FLOAT_EQ(static_cast<float>(*s.rtf), 5.0f);
  EXPECT_FLOAT_EQ(static_cast<float>(*s.speed), 5.0f);
  EXPECT_TRUE(*s.lockstep);
  EXPECT_FALSE(*s.paused);
  EXPECT_EQ(*s.actuator_flags, 15);
  EXPECT_EQ(*s.actuator_armed, 1);
  EXPECT_EQ(s.first_late->late, 5);
  EXPECT_EQ(s.last_late->late, 9);
  EXPECT_EQ(seen.statustext, std::vector<std::string>{text});
}

}  // namespace
}  // namespace hitl::doctor
