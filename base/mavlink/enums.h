// Values of the MAVLink enums hitl uses by name (common.xml / minimal.xml).
#pragma once

#include <cstdint>

namespace hitl::mavlink {

enum class MavType : uint8_t { Generic = 0, Quadrotor = 2, Gcs = 6, Onboard = 18 };
enum class MavAutopilot : uint8_t { Generic = 0, Px4 = 12, Invalid = 8 };
enum class MavState : uint8_t { Uninit = 0, Boot = 1, Calibrating = 2, Standby = 3, Active = 4, Critical = 5, Emergency = 6, Poweroff = 7 };

/// MAV_MODE_FLAG bits of HEARTBEAT.base_mode (and HIL_ACTUATOR_CONTROLS.mode).
namespace mode_flag {
inline constexpr uint8_t kCustomModeEnabled = 1;
inline constexpr uint8_t kTestEnabled = 2;
inline constexpr uint8_t kAutoEnabled = 4;
inline constexpr uint8_t kGuidedEnabled = 8;
inline constexpr uint8_t kStabilizeEnabled = 16;
inline constexpr uint8_t kHilEnabled = 32;
inline constexpr uint8_t kManualInputEnabled = 64;
inline constexpr uint8_t kSafetyArmed = 128;
}  // namespace mode_flag

inline constexpr uint8_t kMavlinkVersion = 3;  ///< HEARTBEAT.mavlink_version

/// MAV_RESULT (COMMAND_ACK.result).
enum class MavResult : uint8_t {
  Accepted = 0, TemporarilyRejected = 1, Denied = 2, Unsupported = 3, Failed = 4, InProgress = 5, Cancelled = 6
};

/// MAV_CMD values hitl sends or answers.
namespace cmd {
inline constexpr uint16_t kNavLand = 21;
inline constexpr uint16_t kNavTakeoff = 22;
inline constexpr uint16_t kDoSetMode = 176;
inline constexpr uint16_t kComponentArmDisarm = 400;
inline constexpr uint16_t kSetMessageInterval = 511;
inline constexpr uint16_t kRequestMessage = 512;
inline constexpr uint16_t kRequestAutopilotCapabilities = 520;
inline constexpr float kArmDisarmForceMagic = 21196.0f;  ///< COMPONENT_ARM_DISARM param2: force
}  // namespace cmd

/// MAV_FRAME values hitl uses (ODOMETRY frame_id / child_frame_id).
enum class MavFrame : uint8_t { LocalNed = 1, BodyFrd = 12, LocalFrd = 20 };
/// MAV_DISTANCE_SENSOR (DISTANCE_SENSOR.type).
enum class MavDistanceSensor : uint8_t { Laser = 0, Ultrasound = 1, Infrared = 2, Radar = 3, Unknown = 4 };
/// MAV_SENSOR_ORIENTATION values hitl uses (DISTANCE_SENSOR.orientation; PX4 maps PITCH_270 to downward-facing).
enum class MavSensorOrientation : uint8_t { None = 0, Pitch90 = 24, Pitch270 = 25 };
/// MAV_ESTIMATOR_TYPE (ODOMETRY.estimator_type).
enum class MavEstimatorType : uint8_t { Unknown = 0, Naive = 1, Vision = 2, Vio = 3, Gps = 4, GpsIns = 5, Mocap = 6, Lidar = 7, Autopilot = 8 };
/// MAV_LANDED_STATE (EXTENDED_SYS_STATE.landed_state).
enum class MavLandedState : uint8_t { Undefined = 0, OnGround = 1, InAir = 2, Takeoff = 3, Landing = 4 };

/// MAV_SEVERITY (STATUSTEXT.severity).
enum class MavSeverity : uint8_t { Emergency = 0, Alert = 1, Critical = 2, Error = 3, Warning = 4, Notice = 5, Info = 6, Debug = 7 };

/// MAV_SYS_STATUS_SENSOR bits (SYS_STATUS onboard_control_sensors_*).
namespace sys_status {
inline constexpr uint32_t kGyro = 1;
inline constexpr uint32_t kAccel = 2;
inline constexpr uint32_t kMag = 4;
inline constexpr uint32_t kAbsolutePressure = 8;
inline constexpr uint32_t kGps = 32;
inline constexpr uint32_t kMotorOutputs = 32768;
inline constexpr uint32_t kRcReceiver = 65536;
inline constexpr uint32_t kAhrs = 2097152;
inline constexpr uint32_t kBattery = 33554432;
inline constexpr uint32_t kPrearmCheck = 268435456;
}  // namespace sys_status

/// ESTIMATOR_STATUS_FLAGS bits (ESTIMATOR_STATUS.flags).
namespace estimator_status {
inline constexpr uint16_t kAttitude = 1;
inline constexpr uint16_t kVelocityHoriz = 2;
inline constexpr uint16_t kVelocityVert = 4;
inline constexpr uint16_t kPosHorizRel = 8;
inline constexpr uint16_t kPosHorizAbs = 16;
inline constexpr uint16_t kPosVertAbs = 32;
inline constexpr uint16_t kPosVertAgl = 64;
inline constexpr uint16_t kConstPosMode = 128;
inline constexpr uint16_t kPredPosHorizRel = 256;
inline constexpr uint16_t kPredPosHorizAbs = 512;
inline constexpr uint16_t kGpsGlitch = 1024;
inline constexpr uint16_t kAccelError = 2048;
}  // namespace estimator_status

/// MAV_PROTOCOL_CAPABILITY bits (AUTOPILOT_VERSION.capabilities).
namespace capability {
inline constexpr uint64_t kCommandInt = 8;
inline constexpr uint64_t kParamEncodeBytewise = 16;
inline constexpr uint64_t kMavlink2 = 8192;
}  // namespace capability

/// MAV_PARAM_TYPE values PX4 uses.
inline constexpr uint8_t kMavParamTypeInt32 = 6;
inline constexpr uint8_t kMavParamTypeReal32 = 9;

/// Component ids hitl uses for itself.
inline constexpr uint8_t kCompIdMissionPlanner = 190;  ///< MAV_COMP_ID_MISSIONPLANNER: what GCS tools use
inline constexpr uint8_t kCompIdPathPlanner = 195;     ///< MAV_COMP_ID_PATHPLANNER: the trajectory pilot in a recording
inline constexpr uint8_t kGcsSystemId = 255;           ///< the system id ground stations use

}  // namespace hitl::mavlink
