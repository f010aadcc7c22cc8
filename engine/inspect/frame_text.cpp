#include "engine/inspect/frame_text.h"

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "engine/mavlink/field_format.h"
#include "engine/telemetry/px4_mode.h"

namespace hitl::inspect {
namespace {

/// custom_mode of a PX4 HEARTBEAT with MAV_MODE_FLAG_CUSTOM_MODE_ENABLED, in the dashboard's words;
/// a word PX4 does not define, or another autopilot's, stays a number.
std::optional<std::string> px4_custom_mode(const mavlink::Frame& frame, const mavlink::FieldDesc& field) {
  if (frame.msgid != mavlink::msg::Heartbeat::kId || field.name != "custom_mode") return std::nullopt;
  const auto hb = frame.as<mavlink::msg::Heartbeat>();
  if (hb.autopilot != static_cast<uint8_t>(mavlink::MavAutopilot::Px4)) return std::nullopt;
  if ((hb.base_mode & mavlink::mode_flag::kCustomModeEnabled) == 0) return std::nullopt;
  const std::string name = telemetry::px4_mode_name(hb.base_mode, hb.custom_mode);
  if (name.rfind("custom ", 0) == 0) return std::nullopt;
  return name.find(' ') == std::string::npos ? name : "\"" + name + "\"";
}

}  // namespace

std::string frame_text(const mavlink::Frame& frame) { return mavlink::format_message(frame, px4_custom_mode); }

}  // namespace hitl::inspect
