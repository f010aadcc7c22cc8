#include "engine/vehicle/trajectory_flight.h"

#include <cmath>
#include <cstdio>

#include "engine/frames/frames.h"
#include "base/mavlink/enums.h"
#include "engine/vehicle/command_client.h"
#include "engine/vehicle/param_client.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
constexpr float kEstimateInterval_us = 20000;  ///< LOCAL_POSITION_NED and ATTITUDE at 50 Hz

std::array<double, 3> minus(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

std::array<double, 3> enu_of(float x_NED, float y_NED, float z_NED) {
  const Eigen::Vector3d v_ENU = frames::ned_to_enu({x_NED, y_NED, z_NED});
  return {v_ENU.x(), v_ENU.y(), v_ENU.z()};
}

bool before_takeoff(PilotState s) { return s == PilotState::Init || s == PilotState::Arm; }

}  // namespace

std::string FlightResult::text() const {
  char line[300];
  int n = std::snprintf(line, sizeof line, "%s%s; %s mode; tracking error (board's estimate) RMS %.2f m, max %.2f m",
                        to_string(state), failure.empty() ? "" : (": " + failure).c_str(), to_string(mode), tracking.rms_m,
                        tracking.max_m);
  if (truth_tracking.samples > 0 && n > 0 && static_cast<std::size_t>(n) < sizeof line)
    std::snprintf(line + n, sizeof line - n, "; against the simulator's truth RMS %.2f m, max %.2f m", truth_tracking.rms_m,
                  truth_tracking.max_m);
  return line;
}

TrajectoryFlight::TrajectoryFlight(Trajectory trajectory, PilotConfig config, bool keep_trace)
    : pilot_(std::move(trajectory), config), mode_(config.mode), keep_trace_(keep_trace) {}

PilotOutput TrajectoryFlight::step(double t_s, const PilotPose& pose, const std::optional<PilotPose>& truth) {
  if (!start_s_) start_s_ = t_s;
  if (!origin_) origin_ = pose;
  const double flight_t_s = t_s - *start_s_;
  PilotPose from_start = pose;
  from_start.p_ENU_m = minus(pose.p_ENU_m, origin_->p_ENU_m);
  std::optional<PilotPose> truth_from_start;
  if (truth && !truth_origin_ && before_takeoff(pilot_.state())) truth_origin_ = truth;  // at rest, as the pose's origin
  if (truth && truth_origin_) {
    truth_from_start = *truth;
    truth_from_start->p_ENU_m = minus(truth->p_ENU_m, truth_origin_->p_ENU_m);
    pilot_.observe_truth(flight_t_s, *truth_from_start);
  }
  auto out = pilot_.step(flight_t_s, from_start);
  if (out.reference)
    for (std::size_t k = 0; k < 3; ++k) out.reference->p_ENU_m[k] += origin_->p_ENU_m[k];  // back to the pose's frame
  if (keep_trace_ && pilot_.state() == PilotState::Trajectory)
    trace_.push_back({flight_t_s, from_start.p_ENU_m,
                      truth_from_start ? std::optional(truth_from_start->p_ENU_m) : std::nullopt});
  return out;
}

FlightResult TrajectoryFlight::result() const {
  FlightResult r;
  r.state = pilot_.state();
  r.failure = pilot_.failure();
  r.mode = mode_;
  r.tracking = pilot_.tracking();
  r.truth_tracking = pilot_.truth_tracking();
  r.trace = trace_;
  return r;
}

Expected<FlightResult> fly_trajectory(VehicleLink& link, Trajectory trajectory, const FlyTrajectoryOptions& options,
                                      const FlightNotes& notes) {
  const auto note = [&](const std::string& text) {
    if (notes) notes(text);
  };
  const auto stopped = [&] { return options.stop && options.stop->load(); };
  CommandClient commands(link);
  for (uint32_t id : {msg::LocalPositionNed::kId, msg::Attitude::kId}) {
    auto r = commands.send(mavlink::cmd::kSetMessageInterval, {static_cast<float>(id), kEstimateInterval_us, 0, 0, 0, 0, 0});
    if (!r || !r->accepted()) note("the board did not take a 50 Hz stream request; flying on its default rates");
  }
  PilotConfig pc;
  pc.rc_rate_hz = options.rc_rate_hz;
  pc.mode = options.mode;
  pc.target_system = link.target_sysid();
  pc.target_component = link.target_compid();
  if (options.mode == StickMode::Attitude) {  // the board's own Stabilized stick scaling
    ParamClient params(link);
    const std::pair<const char*, double*> wanted[] = {{"MPC_MAN_TILT_MAX", &pc.max_tilt_rad}, {"MPC_THR_HOVER", &pc.thr_hover},
                                                      {"MPC_MANTHR_MIN", &pc.thr_min}, {"MPC_THR_MAX", &pc.thr_max}};
    for (const auto& [name, value] : wanted) {
      if (auto p = params.get(name)) *value = std::string(name) == "MPC_MAN_TILT_MAX" ? p->as_double() * M_PI / 180.0 : p->as_double();
      else note(std::string("could not read ") + name + " (" + p.error().message + "); assuming PX4's default");
    }
  }

  // The board's estimate (NED, converted once per frame) and clock; the simulator's truth if heard.
  std::optional<double> home_amsl_m;
  double t_s = 0;
  bool have_position = false, have_yaw = false;
  PilotPose estimate;
  std::optional<PilotPose> truth;
  if (options.truth_sysid) {
    link.on_other_systems([&](const mavlink::Frame& f) {
      if (f.sysid != *options.truth_sysid || !f.is<msg::Odometry>()) return;
      const auto odo = f.as<msg::Odometry>();
      if (odo.estimator_type != static_cast<uint8_t>(mavlink::MavEstimatorType::Mocap)) return;
      truth.emplace();
      truth->p_ENU_m = enu_of(odo.x, odo.y, odo.z);
    });
  }
  std::optional<TrajectoryFlight> flight;
  std::optional<PilotRecord> record;
  if (options.record) {
    link.record_frames(options.record);
    record.emplace(options.record, options.record_sysid);
  }
  auto on_frame = [&](const mavlink::Frame& f) {
    if (f.is<msg::GlobalPositionInt>() && !home_amsl_m) {
      const auto p = f.as<msg::GlobalPositionInt>();
      home_amsl_m = (p.alt - p.relative_alt) / 1000.0;
    } else if (f.is<msg::Attitude>()) {
      estimate.yaw_ENU_rad = frames::yaw_ENU_from_heading_rad(f.as<msg::Attitude>().yaw);
      have_yaw = true;
    } else if (f.is<msg::LocalPositionNed>()) {
      const auto l = f.as<msg::LocalPositionNed>();
      estimate.p_ENU_m = enu_of(l.x, l.y, l.z);
      estimate.v_ENU_m_s = enu_of(l.vx, l.vy, l.vz);
      have_position = true;
      t_s = l.time_boot_ms / 1000.0;
    }
    if (flight) flight->on_board_frame(f);
    return false;
  };
  // Wait for the estimate and home before the pilot starts.
  link.wait(options.estimate_wait_s, [&](const mavlink::Frame& f) {
    on_frame(f);
    return home_amsl_m && have_position && have_yaw;
  });
  const auto forget_truth = [&] {  // the handlers refer to this frame's locals
    link.on_other_systems({});
    link.record_frames({});
  };
  if (!home_amsl_m || !have_position) {
    forget_truth();
    if (stopped()) return FlightResult{PilotState::Init, "", true, options.mode, {}, {}, {}};
    return Error::failed("no position estimate from the board (LOCAL_POSITION_NED, GLOBAL_POSITION_INT)");
  }
  pc.home_alt_msl_m = *home_amsl_m;
  flight.emplace(std::move(trajectory), pc, options.keep_trace);
  while (!flight->finished() && !stopped()) {
    link.wait(0.02, on_frame);
    auto out = flight->step(t_s, estimate, truth);  // the latest LOCAL_POSITION_NED, the latest ATTITUDE's yaw
    for (const auto& c : out.commands) link.send(c);
    if (out.rc) link.send(*out.rc);
    if (out.manual) link.send(*out.manual);
    if (out.event) note(*out.event);
    if (options.on_tracking_error && out.tracking_error_m) options.on_tracking_error(*out.tracking_error_m);
    if (record && out.reference) record->setpoint(static_cast<uint32_t>(t_s * 1000), *out.reference, out.tracking_error_m);
    if (record && out.event) record->note(flight->state() == PilotState::Failed ? Severity::Error : Severity::Info, *out.event);
  }
  forget_truth();
  auto result = flight->result();
  result.stopped = !flight->finished();
  return result;
}

}  // namespace hitl::vehicle
