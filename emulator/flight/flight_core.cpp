#include "emulator/flight/flight_core.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "emulator/flight/attitude_control.h"

namespace hitl::flight {
namespace {

constexpr double kTakeoffGroundPhase_m = 0.3;   // no horizontal position control below this climb
constexpr double kTakeoffDoneTolerance_m = 0.15;
constexpr double kDgyroCutoff_hz = 30.0;        // PX4 IMU_DGYRO_CUTOFF
constexpr double kLandingThrustRamp_per_s = 0.5;

double seconds(std::uint64_t later_us, std::uint64_t earlier_us) {
  return later_us >= earlier_us ? static_cast<double>(later_us - earlier_us) * 1e-6 : 0.0;
}

}  // namespace

std::string to_string(CommandResult result) {
  switch (result) {
    case CommandResult::Accepted: return "Accepted";
    case CommandResult::TemporarilyRejected: return "TemporarilyRejected";
    case CommandResult::Denied: return "Denied";
    case CommandResult::Failed: return "Failed";
  }
  return "Unknown";
}

FlightCore::FlightCore(const FlightParams& params) : params_(params), estimator_(params_) {}

void FlightCore::say(Severity sev, std::string text) { messages_.push_back({sev, std::move(text)}); }

std::vector<StatusMessage> FlightCore::take_messages() {
  std::vector<StatusMessage> out;
  out.swap(messages_);
  return out;
}

void FlightCore::handle_sticks(const StickInput& sticks) {
  sticks_ = sticks;
  sticks_seen_ = true;
}

bool FlightCore::sticks_fresh() const {
  return sticks_seen_ && seconds(std::max(now_us_, sticks_.time_us), sticks_.time_us) <= params_.COM_RC_LOSS_T;
}

StickInput FlightCore::current_sticks() const {
  if (sticks_fresh()) return sticks_;
  StickInput centred;
  centred.time_us = now_us_;
  return centred;
}

bool FlightCore::sticks_deflected_for_override() const {
  if ((params_.COM_RC_OVERRIDE & 1) == 0 || !sticks_fresh()) return false;
  const double limit = params_.COM_RC_STICK_OV / 100.0;
  return std::abs(sticks_.roll) > limit || std::abs(sticks_.pitch) > limit || std::abs(sticks_.yaw) > limit ||
         std::abs(2.0 * (sticks_.throttle - 0.5)) > limit;
}

void FlightCore::set_home() {
  const Estimate& e = estimator_.estimate();
  home_.valid = e.global_valid;
  home_.p_NED_m = e.p_NED_m;
  home_.lat_deg = e.lat_deg;
  home_.lon_deg = e.lon_deg;
  home_.alt_msl_m = e.alt_msl_m;
  home_.yaw_rad = e.yaw_rad;
}

void FlightCore::reset_controllers() {
  position_control_.reset();
  rate_control_.reset();
  land_detector_.reset();
  thrust_limit_ = kNaN;
}

CommandReply FlightCore::arm(bool force) {
  if (armed_) return {CommandResult::Accepted, ""};
  if (!force) {
    const Readiness r = estimator_.preflight_check();
    if (!r.ready) {
      say(Severity::Error, r.reason);
      return {CommandResult::Denied, r.reason};
    }
  }
  armed_ = true;
  landed_state_ = LandedState::OnGround;
  flown_since_arming_ = false;
  on_ground_since_us_ = now_us_;
  set_home();
  reset_controllers();
  hold_NED_m_ = estimator_.estimate().p_NED_m;
  yaw_sp_rad_ = estimator_.estimate().yaw_rad;
  say(Severity::Info, force ? "Armed by external command (forced)" : "Armed by external command");
  return {CommandResult::Accepted, ""};
}

void FlightCore::do_disarm(const char* why) {
  armed_ = false;
  landed_state_ = LandedState::OnGround;
  reset_controllers();
  say(Severity::Info, why);
}

CommandReply FlightCore::disarm(bool force) {
  if (!armed_) return {CommandResult::Accepted, ""};
  if (!force && landed_state_ != LandedState::OnGround) {
    const std::string reason = "Disarming denied: not landed";
    say(Severity::Error, reason);
    return {CommandResult::Denied, reason};
  }
  do_disarm("Disarmed by external command");
  return {CommandResult::Accepted, ""};
}

CommandReply FlightCore::takeoff(const TakeoffRequest& request) {
  if (!armed_) {
    const std::string reason = "Takeoff denied: disarmed";
    say(Severity::Error, reason);
    return {CommandResult::Denied, reason};
  }
  const Estimate& e = estimator_.estimate();
  if (!e.xy_valid || !e.z_valid) {
    const std::string reason = "Takeoff denied: no position estimate";
    say(Severity::Error, reason);
    return {CommandResult::Denied, reason};
  }
  double target_z_m = home_.p_NED_m.z() - params_.MIS_TAKEOFF_ALT;
  if (std::isfinite(request.altitude_m)) {
    target_z_m = request.relative_to_home ? home_.p_NED_m.z() - request.altitude_m
                                          : e.origin_alt_msl_m - request.altitude_m;
  }
  if (target_z_m > e.p_NED_m.z() - 0.5 && landed_state_ == LandedState::OnGround) {
    const std::string reason = "Takeoff denied: altitude below the vehicle";
    say(Severity::Error, reason);
    return {CommandResult::Denied, reason};
  }
  takeoff_target_z_m_ = target_z_m;
  takeoff_xy_NED_m_ = landed_state_ == LandedState::OnGround ? Eigen::Vector2d(e.p_NED_m.head<2>())
                                                               : Eigen::Vector2d(hold_NED_m_.head<2>());
  takeoff_start_z_m_ = e.p_NED_m.z();
  takeoff_ramp_z_m_ = e.p_NED_m.z();
  if (landed_state_ == LandedState::OnGround) {
    reset_controllers();
    landed_state_ = LandedState::Takeoff;
    flown_since_arming_ = true;
    yaw_sp_rad_ = e.yaw_rad;
  }
  mode_ = FlightMode::Takeoff;
  char buf[80];
  std::snprintf(buf, sizeof(buf), "Takeoff to %.1f m above home", home_.p_NED_m.z() - target_z_m);
  say(Severity::Info, buf);
  return {CommandResult::Accepted, ""};
}

CommandReply FlightCore::land() {
  enter_mode(FlightMode::Land);
  return {CommandResult::Accepted, ""};
}

CommandReply FlightCore::set_mode(FlightMode mode) {
  if (mode == FlightMode::Takeoff) return takeoff({});
  if (mode == FlightMode::Stabilized && !sticks_fresh()) {  // PX4's mode requirement: manual control
    const std::string reason = "Switching to Stabilized is currently not possible: no manual control input";
    say(Severity::Error, reason);
    return {CommandResult::Denied, reason};
  }
  enter_mode(mode);
  return {CommandResult::Accepted, ""};
}

void FlightCore::enter_mode(FlightMode mode) {
  const Estimate& e = estimator_.estimate();
  if (mode == mode_ && mode != FlightMode::Takeoff) return;
  mode_ = mode;
  hold_NED_m_ = e.p_NED_m;
  switch (mode) {
    case FlightMode::Position: manual_.reset(e.p_NED_m, yaw_sp_rad_); break;
    case FlightMode::Stabilized: manual_attitude_.reset(e.yaw_rad); break;
    case FlightMode::Hold:
      if (landed_state_ == LandedState::InAir) {
        // Brake: hold where the vehicle would stop at its current speed.
        hold_NED_m_ = e.p_NED_m;
      }
      break;
    case FlightMode::Land:
      if (armed_ && landed_state_ != LandedState::OnGround) {
        landed_state_ = LandedState::Landing;
        say(Severity::Info, "Landing at current position");
      }
      land_detector_.reset();
      thrust_limit_ = kNaN;
      break;
    case FlightMode::Takeoff: break;
  }
}

PositionSetpoint FlightCore::setpoint_for_mode(double dt_s) {
  const Estimate& e = estimator_.estimate();
  PositionSetpoint sp;
  sp.yaw_rad = yaw_sp_rad_;
  switch (mode_) {
    case FlightMode::Takeoff: {
      takeoff_ramp_z_m_ = std::max(takeoff_target_z_m_, takeoff_ramp_z_m_ - params_.MPC_TKO_SPEED * dt_s);
      const bool ramping = takeoff_ramp_z_m_ > takeoff_target_z_m_;
      sp.p_NED_m.z() = takeoff_ramp_z_m_;
      sp.v_NED_m_s.z() = ramping ? -params_.MPC_TKO_SPEED : 0.0;
      const bool on_ground_phase = takeoff_start_z_m_ - e.p_NED_m.z() < kTakeoffGroundPhase_m &&
                                   landed_state_ == LandedState::Takeoff;
      position_control_.freeze_horizontal_integral(on_ground_phase);
      if (!on_ground_phase) sp.p_NED_m.head<2>() = takeoff_xy_NED_m_;  // else: zero horizontal velocity
      if (!ramping && std::abs(e.p_NED_m.z() - takeoff_target_z_m_) < kTakeoffDoneTolerance_m) {
        position_control_.freeze_horizontal_integral(false);
        landed_state_ = LandedState::InAir;
        mode_ = FlightMode::Hold;
        hold_NED_m_ << takeoff_xy_NED_m_, takeoff_target_z_m_;
        say(Severity::Info, "Takeoff complete, holding");
      }
      break;
    }
    case FlightMode::Hold:
      sp.p_NED_m = hold_NED_m_;
      break;
    case FlightMode::Land:
      sp.p_NED_m.head<2>() = hold_NED_m_.head<2>();
      sp.v_NED_m_s.z() = params_.MPC_LAND_SPEED;
      break;
    case FlightMode::Position: {
      sp = manual_.update(current_sticks(), e.p_NED_m, e.v_NED_m_s, e.yaw_rad, params_, dt_s);
      yaw_sp_rad_ = sp.yaw_rad;
      break;
    }
    case FlightMode::Stabilized: break;  // no position setpoint: see step()
  }
  return sp;
}

void FlightCore::idle_outputs() {
  actuators_.u.fill(armed_ ? static_cast<double>(params_.HITL_MOT_IDLE) : 0.0);
  control_ = ControlSnapshot{};
}

void FlightCore::run_controllers(const PositionSetpoint& sp, double dt_s) {
  const Estimate& e = estimator_.estimate();
  VehicleKinematics k{e.p_NED_m, e.v_NED_m_s, e.a_NED_m_s2};
  const PositionControlOutput pos = position_control_.update(sp, k, params_, dt_s, thrust_limit_);
  control_.position = sp;
  run_attitude_rate(pos, sp.yawspeed_rad_s, dt_s);
}

void FlightCore::run_attitude_rate(const PositionControlOutput& pos, double yawspeed_rad_s, double dt_s) {
  const Estimate& e = estimator_.estimate();
  const QuadGeometry geometry = geometry_from(params_);
  if (!mixer_ || mixer_->geometry() != geometry) mixer_.emplace(geometry);
  const Eigen::Vector3d rate_sp = attitude_control(e.q_FRD_to_NED, pos.q_sp_FRD_to_NED, yawspeed_rad_s, params_);

  const double alpha = dt_s / (dt_s + 1.0 / (2.0 * std::numbers::pi * kDgyroCutoff_hz));
  angular_accel_FRD_rad_s2_ += alpha * ((e.w_FRD_rad_s - last_rate_FRD_rad_s_) / dt_s - angular_accel_FRD_rad_s2_);
  last_rate_FRD_rad_s_ = e.w_FRD_rad_s;
  const Eigen::Vector3d torque =
      rate_control_.update(rate_sp, e.w_FRD_rad_s, angular_accel_FRD_rad_s2_, dt_s, false, params_,
                           last_mix_.saturated_positive, last_mix_.saturated_negative);
  last_mix_ = mixer_->mix(torque, pos.collective_thrust, params_.THR_MDL_FAC);
  for (std::size_t i = 0; i < 4; ++i) {
    actuators_.u[i] = std::clamp(std::max(last_mix_.u[i], static_cast<double>(params_.HITL_MOT_IDLE)), 0.0, 1.0);
  }
  control_.position_out = pos;
  control_.rate_sp_FRD_rad_s = rate_sp;
  control_.torque_FRD = torque;
  control_.motor_thrust = last_mix_.thrust;
}

void FlightCore::step(std::uint64_t now_us) {
  const double dt_s = stepped_ ? std::clamp(seconds(now_us, now_us_), 1e-4, 0.05) : 0.004;
  stepped_ = true;
  now_us_ = now_us;
  estimator_.set_armed(armed_);
  const Estimate& e = estimator_.estimate();
  if (!home_.valid && !armed_ && e.global_valid) set_home();

  actuators_.time_us = now_us;
  if (!armed_) {
    actuators_.u.fill(0.0);
    actuators_.armed = false;
    actuators_.mode = base_mode();
    control_ = ControlSnapshot{};
    return;
  }

  // PX4 reports TAKEOFF only while its takeoff runs: left in the climb (a pilot switching to
  // Position, Hold), the vehicle clear of the ground is IN_AIR from then on.
  if (landed_state_ == LandedState::Takeoff && mode_ != FlightMode::Takeoff &&
      takeoff_start_z_m_ - e.p_NED_m.z() >= kTakeoffGroundPhase_m) {
    position_control_.freeze_horizontal_integral(false);
    landed_state_ = LandedState::InAir;
  }

  // Sticks take over from auto modes (COM_RC_OVERRIDE).
  if ((mode_ == FlightMode::Hold || mode_ == FlightMode::Land) && landed_state_ != LandedState::OnGround &&
      sticks_deflected_for_override()) {
    enter_mode(FlightMode::Position);
    landed_state_ = LandedState::InAir;
    say(Severity::Info, "Pilot took over position control using sticks");
  }

  // Stabilized without sticks has nothing to fly by: hold position instead (PX4's RC-loss failsafe).
  if (mode_ == FlightMode::Stabilized && landed_state_ != LandedState::OnGround && !sticks_fresh()) {
    enter_mode(FlightMode::Hold);
    say(Severity::Warning, "Manual control lost: switching to Hold");
  }

  if (landed_state_ == LandedState::OnGround) {
    // Position and Stabilized: throttle up lifts off.
    const bool manual_mode = mode_ == FlightMode::Position || mode_ == FlightMode::Stabilized;
    if (manual_mode && ManualPositionSetpoint::wants_climb(current_sticks(), params_)) {
      reset_controllers();
      manual_.reset(e.p_NED_m, e.yaw_rad);
      manual_attitude_.reset(e.yaw_rad);
      landed_state_ = LandedState::InAir;
      flown_since_arming_ = true;
      say(Severity::Info, "Takeoff detected");
    } else {
      const double on_ground_s = seconds(now_us, on_ground_since_us_);
      if (!flown_since_arming_ && params_.COM_DISARM_PRFLT > 0.0 && on_ground_s > params_.COM_DISARM_PRFLT) {
        do_disarm("Disarmed by auto preflight disarming");
      } else if (flown_since_arming_ && params_.COM_DISARM_LAND > 0.0 && on_ground_s > params_.COM_DISARM_LAND) {
        do_disarm("Disarmed by landing");
      }
      idle_outputs();
      actuators_.armed = armed_;
      actuators_.mode = base_mode();
      if (!armed_) actuators_.u.fill(0.0);
      return;
    }
  }

  if (mode_ == FlightMode::Stabilized) {
    const AttitudeSetpoint att = manual_attitude_.update(current_sticks(), params_, dt_s);
    yaw_sp_rad_ = manual_attitude_.yaw_sp_rad();
    PositionControlOutput pos;
    pos.q_sp_FRD_to_NED = att.q_sp_FRD_to_NED;
    pos.collective_thrust = std::isnan(thrust_limit_) ? att.collective_thrust : std::min(att.collective_thrust, thrust_limit_);
    pos.thrust_NED = att.q_sp_FRD_to_NED * Eigen::Vector3d(0.0, 0.0, -pos.collective_thrust);
    control_.position = PositionSetpoint{};
    run_attitude_rate(pos, att.yawspeed_rad_s, dt_s);
  } else {
    run_controllers(setpoint_for_mode(dt_s), dt_s);
  }

  // Touchdown: in the air or landing, never while taking off.
  if (landed_state_ == LandedState::InAir || landed_state_ == LandedState::Landing) {
    LandDetectorInput in{e.v_NED_m_s, control_.position_out.v_sp_NED_m_s, e.w_FRD_rad_s,
                         control_.position_out.collective_thrust};
    const bool landed = land_detector_.update(in, params_, dt_s);
    control_.ground_contact = land_detector_.ground_contact();
    if (land_detector_.ground_contact()) {
      const double from = std::isnan(thrust_limit_) ? control_.position_out.collective_thrust : thrust_limit_;
      thrust_limit_ = std::max(static_cast<double>(params_.MPC_THR_MIN), from - kLandingThrustRamp_per_s * dt_s);
    } else {
      thrust_limit_ = kNaN;
    }
    if (landed) {
      landed_state_ = LandedState::OnGround;
      on_ground_since_us_ = now_us;
      reset_controllers();
      say(Severity::Info, "Landing detected");
      idle_outputs();
    }
  }
  actuators_.armed = armed_;
  actuators_.mode = base_mode();
}

std::vector<std::string> FlightCore::commander_status_lines() const {
  std::vector<std::string> lines;
  char buf[200];
  std::snprintf(buf, sizeof(buf), "commander: %s, mode %s (custom_mode 0x%08x), %s", armed_ ? "ARMED" : "DISARMED",
                to_string(mode_).c_str(), static_cast<unsigned>(custom_mode()), to_string(landed_state_).c_str());
  lines.emplace_back(buf);
  const Readiness r = estimator_.preflight_check();
  lines.push_back(r.ready ? "  preflight checks: pass" : "  preflight checks: " + r.reason);
  if (home_.valid) {
    std::snprintf(buf, sizeof(buf), "  home: lat %.7f lon %.7f alt %.2f m AMSL", home_.lat_deg, home_.lon_deg,
                  home_.alt_msl_m);
    lines.emplace_back(buf);
  } else {
    lines.emplace_back("  home: not set");
  }
  const auto& u = actuators_.u;
  std::snprintf(buf, sizeof(buf), "  motors: %.3f %.3f %.3f %.3f, thrust %.3f", u[0], u[1], u[2], u[3],
                control_.position_out.collective_thrust);
  lines.emplace_back(buf);
  return lines;
}

}  // namespace hitl::flight
