// What a ground station knows about the vehicle from the autopilot's telemetry, folded frame by
// frame into one value: HEARTBEAT (armed, mode), EXTENDED_SYS_STATE (landed state), SYS_STATUS
// (prearm check, battery), BATTERY_STATUS, ESTIMATOR_STATUS, LOCAL_POSITION_NED,
// ATTITUDE_QUATERNION, GLOBAL_POSITION_INT. Unset optionals are messages not heard yet.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "base/mavlink/frame.h"

namespace hitl::telemetry {

struct EstimatorStatusValues {
  uint16_t flags = 0;
  double vel_ratio = 0;
  double pos_horiz_ratio = 0;
  double pos_vert_ratio = 0;
  double mag_ratio = 0;
  double hagl_ratio = 0;
  double tas_ratio = 0;
  double pos_horiz_accuracy_m = 0;
  double pos_vert_accuracy_m = 0;
};

/// The values of an ESTIMATOR_STATUS frame (`f` must be one), for every reader of that message.
EstimatorStatusValues estimator_status_from(const mavlink::Frame& f);

struct VehicleTelemetry {
  // HEARTBEAT
  bool heartbeat = false;
  bool armed = false;
  std::string mode;               ///< px4_mode_name()
  uint8_t system_status = 0;      ///< MAV_STATE
  // EXTENDED_SYS_STATE
  std::optional<std::string> landed;  ///< "on ground", "in air", "taking off", "landing", "undefined"
  bool in_air = false;                ///< landed state in air, taking off or landing
  // SYS_STATUS / BATTERY_STATUS (BATTERY_STATUS wins when both are heard)
  std::optional<bool> ready_to_arm;   ///< SYS_STATUS prearm check health bit
  std::optional<double> battery_V;
  std::optional<double> battery_A;
  std::optional<double> battery_remaining_pct;
  // estimator
  std::optional<EstimatorStatusValues> estimator;
  std::optional<std::array<double, 3>> p_NED_m;      ///< LOCAL_POSITION_NED
  std::optional<std::array<double, 3>> v_NED_m_s;
  std::optional<std::array<double, 4>> q_FRD_to_NED;  ///< ATTITUDE_QUATERNION, w x y z
  std::optional<double> relative_alt_m;                ///< GLOBAL_POSITION_INT
  /// When each message was last heard (monotonic seconds), by id.
  std::map<uint32_t, double> last_heard_s;
};

/// MAV_LANDED_STATE in words.
std::string landed_state_name(uint8_t landed_state);

class VehicleTelemetryTracker {
 public:
  /// Folds one frame from the autopilot heard at `now_s`; frames of other messages are ignored.
  void on_frame(const mavlink::Frame& frame, double now_s);
  const VehicleTelemetry& state() const { return state_; }

 private:
  VehicleTelemetry state_;
  bool battery_status_heard_ = false;
};

}  // namespace hitl::telemetry
