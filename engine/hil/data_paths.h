// The spec's "Data Flow Rates" as the host sees them, live: what the session sends (IMU, mag and
// baro by the fields_updated of each HIL_SENSOR, HIL_GPS, ODOMETRY) and what comes back
// (HIL_ACTUATOR_CONTROLS), each with its expected rate, measured rate, jitter and, for what comes
// back, the frames lost on the board's link (sequence gaps).
//
// Expected rates scale with the pace the session holds (--speed, or the measured real-time factor
// when running as fast as possible): at --speed 5 the IMU is expected at 1250 Hz of wall time.
// Actuators: one answer per sensor message in lockstep, else the board's own 200 Hz stream (spec).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "base/mavlink/frame.h"
#include "base/mavlink/sequence_tracker.h"
#include "engine/hil/session_config.h"
#include "engine/telemetry/stream_meter.h"

namespace hitl::hil {

using ::hitl::kActuatorStreamRate_hz;  // base/contract/data_rates.h

struct DataPathStats {
  std::string name;          ///< "IMU", "mag", "baro", "GPS", "ODOMETRY", "actuators"
  std::string message;       ///< the MAVLink message carrying it
  bool outgoing = true;      ///< host -> board
  double expected_hz = 0;    ///< at the current pace (wall time)
  telemetry::StreamStats stats;
  std::optional<double> loss_pct;  ///< incoming only: frames lost on the board's link, last window
};

class DataPaths {
 public:
  /// The paths this configuration has (no ODOMETRY with --no-vio); `lockstep`: the flight stack
  /// answers each sensor message (StackPeer::lockstep()).
  DataPaths(const SessionConfig& config, bool lockstep);

  void on_hil_sensor(bool imu, bool mag, bool baro, double now_s);
  void on_hil_gps(double now_s);
  void on_odometry(double now_s);
  /// Every frame from the flight stack: actuators are timed, every frame's sequence counts for loss.
  void on_stack_frame(const mavlink::Frame& frame, double now_s);
  /// Closes the window at `now_s`; `pace` is the real-time factor expected rates scale with.
  void roll(double now_s, double pace);
  std::vector<DataPathStats> stats(double now_s) const;

 private:
  struct Path {
    DataPathStats info;
    double base_rate_hz = 0;   ///< at real time
    bool scales_with_pace = true;
    telemetry::StreamMeter meter;
  };
  Path& path(std::size_t index) { return paths_[index]; }

  std::vector<Path> paths_;
  std::optional<std::size_t> odometry_;
  std::map<std::tuple<uint8_t, uint8_t>, mavlink::SequenceTracker> stack_sequences_;
  uint64_t window_start_received_ = 0;
  uint64_t window_start_lost_ = 0;
  std::optional<double> last_loss_pct_;
};

}  // namespace hitl::hil
