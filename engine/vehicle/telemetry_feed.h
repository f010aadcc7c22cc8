// A live view of the vehicle for a dashboard, on its own thread and its own link: connects
// (patiently) to the autopilot, asks it for the streams a dashboard needs with
// MAV_CMD_SET_MESSAGE_INTERVAL (asked again when one stays silent, e.g. after a board restart),
// folds every frame into VehicleTelemetry, hands STATUSTEXT to a callback, and, through a
// session, scores the estimate against the simulator's ground truth (the ODOMETRY the session
// sends its clients from the simulator's system id, estimator type MOCAP).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "base/mavlink/enums.h"
#include "engine/mavlink/statustext.h"
#include "engine/telemetry/estimate_error.h"
#include "engine/telemetry/vehicle_telemetry.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

/// A stream the feed asks for, and how often (the autopilot's clock).
struct StreamRequest {
  uint32_t message_id = 0;
  double rate_hz = 0;
};

/// What a dashboard shows: ESTIMATOR_STATUS 5 Hz, LOCAL_POSITION_NED and ATTITUDE_QUATERNION 10 Hz,
/// EXTENDED_SYS_STATE 2 Hz, HEARTBEAT, SYS_STATUS, BATTERY_STATUS 1 Hz, GLOBAL_POSITION_INT 5 Hz.
std::vector<StreamRequest> dashboard_streams();

struct TelemetryFeedSnapshot {
  bool connected = false;
  std::string link;                  ///< VehicleLink::description(), or why there is none yet
  telemetry::VehicleTelemetry vehicle;
  telemetry::EstimateError estimate_error;
  bool truth_heard = false;          ///< the simulator's truth reaches this link
  uint64_t requests_refused = 0;     ///< SET_MESSAGE_INTERVAL answered with anything but ACCEPTED
};

class TelemetryFeed {
 public:
  /// The autopilot's STATUSTEXT, and the feed's own news (connected) at severity Info.
  using TextSink = std::function<void(mavlink::MavSeverity, const std::string&)>;

  /// `truth_sysid`: the system whose ODOMETRY (type MOCAP) is the ground truth (a session's
  /// simulator); none outside a simulation.
  TelemetryFeed(LinkOptions options, std::vector<StreamRequest> streams, TextSink statustext,
                std::optional<uint8_t> truth_sysid);
  ~TelemetryFeed();  ///< stops and joins
  TelemetryFeed(const TelemetryFeed&) = delete;
  TelemetryFeed& operator=(const TelemetryFeed&) = delete;

  TelemetryFeedSnapshot snapshot() const;
  void stop();

 private:
  void run();
  void request_streams(VehicleLink& link, double now_s, bool all);
  /// Whole status texts to the sink, control characters made spaces (nothing from the network
  /// reaches the terminal as one).
  void show(const std::vector<mavlink::StatusText>& texts);
  void on_truth(const mavlink::Frame& frame);

  LinkOptions options_;
  std::vector<StreamRequest> streams_;
  std::optional<uint8_t> truth_sysid_;
  std::vector<double> requested_at_s_;
  TextSink statustext_;
  mavlink::StatusTextAssembler statustexts_;  // the feed's thread only
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  TelemetryFeedSnapshot published_;
  // owned by the thread
  telemetry::VehicleTelemetryTracker tracker_;
  telemetry::EstimateErrorMeter error_meter_;
  std::optional<telemetry::TruthPose> truth_;
  std::optional<double> rest_down_m_;  ///< truth's down coordinate at rest on the ground
  std::thread thread_;
};

}  // namespace hitl::vehicle
