#include "engine/mavlink/enum_names.h"

#include <cstdio>
#include <vector>

#include "base/mavlink/enums.h"

namespace hitl::mavlink {
namespace {

struct Named {
  uint64_t value;
  std::string_view name;
};

template <class E>
constexpr Named v(E value, std::string_view name) {
  return {static_cast<uint64_t>(value), name};
}

struct Table {
  std::string_view enum_name;
  bool bitmask;
  std::vector<Named> values;
};

// Every value below is a constant of enums.h; the names are the dialect's less the enum's prefix.
const Table kTables[] = {
    {"MAV_TYPE", false,
     {v(MavType::Generic, "GENERIC"), v(MavType::Quadrotor, "QUADROTOR"), v(MavType::Gcs, "GCS"),
      v(MavType::Onboard, "ONBOARD_CONTROLLER")}},
    {"MAV_AUTOPILOT", false,
     {v(MavAutopilot::Generic, "GENERIC"), v(MavAutopilot::Px4, "PX4"), v(MavAutopilot::Invalid, "INVALID")}},
    {"MAV_STATE", false,
     {v(MavState::Uninit, "UNINIT"), v(MavState::Boot, "BOOT"), v(MavState::Calibrating, "CALIBRATING"),
      v(MavState::Standby, "STANDBY"), v(MavState::Active, "ACTIVE"), v(MavState::Critical, "CRITICAL"),
      v(MavState::Emergency, "EMERGENCY"), v(MavState::Poweroff, "POWEROFF")}},
    {"MAV_MODE_FLAG", true,
     {v(mode_flag::kCustomModeEnabled, "CUSTOM_MODE_ENABLED"), v(mode_flag::kTestEnabled, "TEST_ENABLED"),
      v(mode_flag::kAutoEnabled, "AUTO_ENABLED"), v(mode_flag::kGuidedEnabled, "GUIDED_ENABLED"),
      v(mode_flag::kStabilizeEnabled, "STABILIZE_ENABLED"), v(mode_flag::kHilEnabled, "HIL_ENABLED"),
      v(mode_flag::kManualInputEnabled, "MANUAL_INPUT_ENABLED"), v(mode_flag::kSafetyArmed, "SAFETY_ARMED")}},
    {"MAV_RESULT", false,
     {v(MavResult::Accepted, "ACCEPTED"), v(MavResult::TemporarilyRejected, "TEMPORARILY_REJECTED"),
      v(MavResult::Denied, "DENIED"), v(MavResult::Unsupported, "UNSUPPORTED"), v(MavResult::Failed, "FAILED"),
      v(MavResult::InProgress, "IN_PROGRESS"), v(MavResult::Cancelled, "CANCELLED")}},
    {"MAV_SEVERITY", false,
     {v(MavSeverity::Emergency, "EMERGENCY"), v(MavSeverity::Alert, "ALERT"), v(MavSeverity::Critical, "CRITICAL"),
      v(MavSeverity::Error, "ERROR"), v(MavSeverity::Warning, "WARNING"), v(MavSeverity::Notice, "NOTICE"),
      v(MavSeverity::Info, "INFO"), v(MavSeverity::Debug, "DEBUG")}},
    {"MAV_CMD", false,
     {v(cmd::kNavLand, "NAV_LAND"), v(cmd::kNavTakeoff, "NAV_TAKEOFF"), v(cmd::kDoSetMode, "DO_SET_MODE"),
      v(cmd::kComponentArmDisarm, "COMPONENT_ARM_DISARM"), v(cmd::kSetMessageInterval, "SET_MESSAGE_INTERVAL"),
      v(cmd::kRequestMessage, "REQUEST_MESSAGE"),
      v(cmd::kRequestAutopilotCapabilities, "REQUEST_AUTOPILOT_CAPABILITIES")}},
    {"MAV_FRAME", false,
     {v(MavFrame::LocalNed, "LOCAL_NED"), v(MavFrame::BodyFrd, "BODY_FRD"), v(MavFrame::LocalFrd, "LOCAL_FRD")}},
    {"MAV_ESTIMATOR_TYPE", false,
     {v(MavEstimatorType::Unknown, "UNKNOWN"), v(MavEstimatorType::Naive, "NAIVE"), v(MavEstimatorType::Vision, "VISION"),
      v(MavEstimatorType::Vio, "VIO"), v(MavEstimatorType::Gps, "GPS"), v(MavEstimatorType::GpsIns, "GPS_INS"),
      v(MavEstimatorType::Mocap, "MOCAP"), v(MavEstimatorType::Lidar, "LIDAR"),
      v(MavEstimatorType::Autopilot, "AUTOPILOT")}},
    {"MAV_LANDED_STATE", false,
     {v(MavLandedState::Undefined, "UNDEFINED"), v(MavLandedState::OnGround, "ON_GROUND"),
      v(MavLandedState::InAir, "IN_AIR"), v(MavLandedState::Takeoff, "TAKEOFF"), v(MavLandedState::Landing, "LANDING")}},
    {"MAV_SYS_STATUS_SENSOR", true,
     {v(sys_status::kGyro, "3D_GYRO"), v(sys_status::kAccel, "3D_ACCEL"), v(sys_status::kMag, "3D_MAG"),
      v(sys_status::kAbsolutePressure, "ABSOLUTE_PRESSURE"), v(sys_status::kGps, "GPS"),
      v(sys_status::kMotorOutputs, "MOTOR_OUTPUTS"), v(sys_status::kRcReceiver, "RC_RECEIVER"),
      v(sys_status::kAhrs, "AHRS"), v(sys_status::kBattery, "BATTERY"), v(sys_status::kPrearmCheck, "PREARM_CHECK")}},
    {"MAV_PARAM_TYPE", false, {v(kMavParamTypeInt32, "INT32"), v(kMavParamTypeReal32, "REAL32")}},
};

std::string bits(const Table& table, uint64_t value) {
  if (value == 0) return "0";
  std::string out;
  uint64_t rest = value;
  for (const auto& named : table.values) {
    if ((value & named.value) == 0) continue;
    if (!out.empty()) out += '|';
    out += named.name;
    rest &= ~named.value;
  }
  if (rest != 0) {
    char hex[24];
    std::snprintf(hex, sizeof hex, "0x%llx", static_cast<unsigned long long>(rest));
    if (!out.empty()) out += '|';
    out += hex;
  }
  return out;
}

}  // namespace

std::optional<std::string> enum_value_name(std::string_view enum_name, uint64_t value) {
  for (const auto& table : kTables) {
    if (table.enum_name != enum_name) continue;
    if (table.bitmask) return bits(table, value);
    for (const auto& named : table.values)
      if (named.value == value) return std::string(named.name);
    return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace hitl::mavlink
