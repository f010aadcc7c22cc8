#include "engine/vehicle/pilot_record.h"

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "base/mavlink/severity.h"
#include "base/mavlink/text_field.h"
#include "engine/frames/frames.h"

namespace hitl::vehicle {

namespace {
/// POSITION_TARGET_LOCAL_NED's type_mask: position, velocity and yaw given; acceleration and yaw rate not.
constexpr uint16_t kIgnoreAccelerationAndYawRate = (1u << 6) | (1u << 7) | (1u << 8) | (1u << 11);
}  // namespace

PilotRecord::PilotRecord(Sink sink, uint8_t sysid, mavlink::Version protocol)
    : sink_(std::move(sink)), encoder_(sysid, mavlink::kCompIdPathPlanner, protocol) {}

template <class M>
void PilotRecord::record(const M& message) {
  mavlink::FrameBuffer buf;
  if (const std::size_t n = encoder_.encode(message, buf)) sink_({buf.data(), n});
}

void PilotRecord::setpoint(uint32_t time_boot_ms, const TrajectoryReference& ref, std::optional<double> tracking_error_m) {
  const Eigen::Vector3d p_NED_m = frames::enu_to_ned({ref.p_ENU_m[0], ref.p_ENU_m[1], ref.p_ENU_m[2]});
  const Eigen::Vector3d v_NED_m_s = frames::enu_to_ned({ref.v_ENU_m_s[0], ref.v_ENU_m_s[1], ref.v_ENU_m_s[2]});
  mavlink::msg::PositionTargetLocalNed sp;
  sp.time_boot_ms = time_boot_ms;
  sp.coordinate_frame = static_cast<uint8_t>(mavlink::MavFrame::LocalNed);
  sp.type_mask = kIgnoreAccelerationAndYawRate;
  sp.x = static_cast<float>(p_NED_m.x());
  sp.y = static_cast<float>(p_NED_m.y());
  sp.z = static_cast<float>(p_NED_m.z());
  sp.vx = static_cast<float>(v_NED_m_s.x());
  sp.vy = static_cast<float>(v_NED_m_s.y());
  sp.vz = static_cast<float>(v_NED_m_s.z());
  sp.yaw = static_cast<float>(frames::yaw_ENU_from_heading_rad(ref.yaw_ENU_rad));  // pi/2 - yaw both ways
  record(sp);
  if (!tracking_error_m) return;
  mavlink::msg::NamedValueFloat err;
  err.time_boot_ms = time_boot_ms;
  mavlink::set_text(err.name, kTrackingErrorName);
  err.value = static_cast<float>(*tracking_error_m);
  record(err);
}

void PilotRecord::note(Severity severity, std::string_view text) {
  for (const auto& st : statustext_chunker_.split(static_cast<uint8_t>(mavlink::mav_severity(severity)), text))
    record(st);
}

}  // namespace hitl::vehicle
