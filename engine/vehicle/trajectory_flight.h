// One trajectory flight, however it is fed: the pilot (trajectory_pilot.h), the start its clock,
// pose and truth are measured from (each where it was at the first sample: the vehicle at rest),
// the trace of what was flown, and the result. Two drivers, one flight:
//   fly_trajectory(): over a VehicleLink, on the board's own estimate (LOCAL_POSITION_NED and
//     ATTITUDE at 50 Hz, converted from NED in engine/frames) and the board's clock (time_boot_ms,
//     so any simulator speed works), scored also against a simulator's truth when one is heard;
//     `hitl fly trajectory` and the dashboard's `f` key run it;
//   the session's -t steps a TrajectoryFlight in its own tick, on the simulator's truth.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/common/expected.h"
#include "base/mavlink/enums.h"
#include "engine/vehicle/pilot_record.h"
#include "engine/vehicle/trajectory.h"
#include "engine/vehicle/trajectory_pilot.h"
#include "engine/vehicle/vehicle_link.h"

namespace hitl::vehicle {

/// Where the vehicle was, sampled while the trajectory itself is flown (ENU metres from the start).
struct TracePoint {
  double t_s = 0;
  std::array<double, 3> p_ENU_m{};
  std::optional<std::array<double, 3>> truth_p_ENU_m;
};

struct FlightResult {
  PilotState state = PilotState::Init;  ///< DONE, FAILED, or where it was when stopped
  std::string failure;                  ///< FAILED: why
  bool stopped = false;                 ///< ended by the caller's stop flag before DONE / FAILED
  StickMode mode = StickMode::Velocity;
  TrackingStats tracking;        ///< against the pose it flew on
  TrackingStats truth_tracking;  ///< against the truth, when there was one (samples 0 otherwise)
  std::vector<TracePoint> trace;
  bool ok() const { return state == PilotState::Done; }
  /// "DONE; velocity mode; tracking error (board's estimate) RMS 0.41 m, max 0.93 m; against the
  /// simulator's truth RMS ..."
  std::string text() const;
};

class TrajectoryFlight {
 public:
  /// `keep_trace`: record a TracePoint per step of the trajectory itself (for --json).
  TrajectoryFlight(Trajectory trajectory, PilotConfig config, bool keep_trace = false);

  /// The board's frames: HEARTBEAT (armed), SYS_STATUS (ready to arm), COMMAND_ACK.
  void on_board_frame(const mavlink::Frame& frame) { pilot_.on_board_frame(frame); }
  /// One tick at `t_s` (any clock) on `pose` (world ENU, any origin), scored also against `truth`
  /// (world ENU, its own origin) when given; what to send back. The first tick fixes the start of
  /// the clock and the pose's origin; the truth's origin is its first sample before the takeoff.
  /// The output's reference is in the pose's frame (world ENU).
  PilotOutput step(double t_s, const PilotPose& pose, const std::optional<PilotPose>& truth = std::nullopt);

  PilotState state() const { return pilot_.state(); }
  const std::string& failure() const { return pilot_.failure(); }
  TrackingStats tracking() const { return pilot_.tracking(); }
  bool finished() const { return pilot_.finished(); }
  FlightResult result() const;

 private:
  TrajectoryPilot pilot_;
  StickMode mode_;
  bool keep_trace_;
  std::optional<double> start_s_;
  std::optional<PilotPose> origin_;
  std::optional<PilotPose> truth_origin_;
  std::vector<TracePoint> trace_;
};

struct FlyTrajectoryOptions {
  StickMode mode = StickMode::Velocity;
  double rc_rate_hz = 20;           ///< RC_CHANNELS_OVERRIDE rate
  double estimate_wait_s = 60;      ///< how long to wait for the board's estimate and home before starting
  std::optional<uint8_t> truth_sysid;  ///< a simulator whose ODOMETRY (MOCAP) is ground truth
  bool keep_trace = false;
  const std::atomic<bool>* stop = nullptr;  ///< when it turns true the flight ends (result.stopped)
  /// A recording (hitl fly trajectory --report): every frame read and sent, and the pilot's
  /// setpoints, errors and states (pilot_record.h) as `record_sysid`.
  PilotRecord::Sink record;
  uint8_t record_sysid = mavlink::kGcsSystemId;
  /// Each scored tracking error as it is computed (the dashboard's graph), on the flight's thread.
  std::function<void(double tracking_error_m)> on_tracking_error;
};

/// What the flight says as it goes: a state change ("trajectory: TAKEOFF (armed)") or a note
/// ("the board did not take a 50 Hz stream request; flying on its default rates").
using FlightNotes = std::function<void(const std::string& text)>;

/// The whole flight over `link`: asks for the estimate's streams, reads the board's Stabilized stick
/// scaling (attitude mode), waits for the estimate and home, then flies until DONE / FAILED / stop.
/// An Error when the board gave no position estimate within estimate_wait_s.
Expected<FlightResult> fly_trajectory(VehicleLink& link, Trajectory trajectory, const FlyTrajectoryOptions& options,
                                      const FlightNotes& notes = {});

}  // namespace hitl::vehicle
