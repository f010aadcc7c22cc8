#include "engine/vehicle/firmware_version.h"

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"

namespace hitl::vehicle {

std::string format_flight_sw_version(uint32_t v) {
  std::string text = "v" + std::to_string((v >> 24) & 0xFF) + "." + std::to_string((v >> 16) & 0xFF) + "." +
                     std::to_string((v >> 8) & 0xFF);
  switch (v & 0xFF) {
    case 255: return text;
    case 192: return text + "-rc";
    case 128: return text + "-beta";
    case 64: return text + "-alpha";
    case 0: return text + "-dev";
    default: return text + "-" + std::to_string(v & 0xFF);
  }
}

std::optional<std::string> request_firmware_version(VehicleLink& link, double timeout_s) {
  namespace msg = mavlink::msg;
  msg::CommandLong c;
  c.target_system = link.target_sysid();
  c.target_component = link.target_compid();
  c.command = mavlink::cmd::kRequestMessage;
  c.param1 = static_cast<float>(msg::AutopilotVersion::kId);
  link.send(c);
  std::optional<std::string> version;
  link.wait(timeout_s, [&](const mavlink::Frame& f) {
    if (!f.is<msg::AutopilotVersion>()) return false;
    version = format_flight_sw_version(f.as<msg::AutopilotVersion>().flight_sw_version);
    return true;
  });
  return version;
}

}  // namespace hitl::vehicle
