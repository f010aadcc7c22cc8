// The emulated board's HIL input side, as PX4's MavlinkReceiver takes it: HIL_SENSOR and HIL_GPS
// decoded field by field into target/core's inputs (wire units, no conversion here), and the
// lockstep clock that follows HIL_SENSOR.time_usec.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "base/mavlink/messages.h"
#include "target/core/hil_inputs.h"

namespace hitl::target {

HilSensorInput hil_sensor_input(const mavlink::msg::HilSensor& m);
HilGpsInput hil_gps_input(const mavlink::msg::HilGps& m);

/// Lockstep: the board's clock follows HIL_SENSOR.time_usec from the first one on, continuing from
/// the wall-clock time it had until then (so HEARTBEATs flow before the simulator starts), one IMU
/// period (kHilImuPublishPeriod_us) ahead, so that the split publishes the sample it was just given.
/// A time_usec lower than the last one is a new simulator session (each starts again near 0): the
/// board re-anchors, its own clock carrying on from where it was, as it did for the first.
class LockstepClock {
 public:
  /// The board time after HIL_SENSOR `time_usec` arrived at board time `now_us` (never earlier than
  /// `now_us`). A new simulator session is said in `new_session_text()`.
  uint64_t on_hil_sensor(uint64_t time_usec, uint64_t now_us);

  /// Whether a HIL_SENSOR has set the clock (until then the board runs on the wall clock).
  bool started() const { return started_; }
  /// The last HIL_SENSOR.time_usec: lockstep answers are stamped with it.
  uint64_t last_sensor_time_us() const { return last_sensor_time_us_; }
  /// Simulator sessions after the first (time_usec went back).
  uint64_t restarts() const { return restarts_; }
  /// The latest restart in words, once: cleared by the call.
  std::optional<std::string> take_new_session_text();

 private:
  bool started_ = false;
  uint64_t origin_us_ = 0;  ///< the time_usec the clock anchored at
  uint64_t base_us_ = 0;    ///< the board time it had then
  uint64_t last_sensor_time_us_ = 0;
  uint64_t restarts_ = 0;
  std::optional<std::string> new_session_text_;
};

}  // namespace hitl::target
