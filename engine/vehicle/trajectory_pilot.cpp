#include "engine/vehicle/trajectory_pilot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/mavlink/enums.h"
#include "engine/vehicle/action.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
constexpr double kGravity_m_s2 = 9.80665;
constexpr double kMaxHoverCorrection_m_s2 = 3.0;  ///< the integrator's authority

/// The stick that asks PX4's position mode for `fraction` of full rate: past the deadzone, which PX4
/// cuts out and rescales (MPC_HOLD_DZ), so small corrections are not swallowed. Below a thousandth
/// of full rate (rounding noise, e.g. cos(pi/2)) the stick stays centred instead of jumping to the
/// deadzone's edge.
double stick_for(double fraction, double deadzone) {
  if (std::fabs(fraction) < 1e-3) return 0.0;
  const double f = std::clamp(std::fabs(fraction), 0.0, 1.0);
  return std::copysign(deadzone + (1.0 - deadzone) * f, fraction);
}

uint16_t pwm(double stick) { return static_cast<uint16_t>(std::lround(1500.0 + 500.0 * std::clamp(stick, -1.0, 1.0))); }

/// The velocity the reference asks for here: its own (while flying it) plus a P term on the error.
std::array<double, 3> velocity_setpoint(bool flying, const TrajectoryReference& ref, const PilotPose& pose, double kp_1_s) {
  std::array<double, 3> v{};
  for (std::size_t k = 0; k < 3; ++k) v[k] = (flying ? ref.v_ENU_m_s[k] : 0.0) + kp_1_s * (ref.p_ENU_m[k] - pose.p_ENU_m[k]);
  return v;
}

/// "2.50": a height for an event line.
std::string metres_text(double m) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", m);
  return text;
}

}  // namespace

const char* to_string(PilotState s) {
  switch (s) {
    case PilotState::Init: return "INIT";
    case PilotState::Arm: return "ARM";
    case PilotState::Takeoff: return "TAKEOFF";
    case PilotState::Trajectory: return "TRAJECTORY";
    case PilotState::Hold: return "HOLD";
    case PilotState::Land: return "LAND";
    case PilotState::Disarm: return "DISARM";
    case PilotState::Done: return "DONE";
    case PilotState::Failed: return "FAILED";
  }
  return "?";
}

const char* to_string(StickMode m) { return m == StickMode::Attitude ? "attitude" : "velocity"; }

void TrajectoryPilot::ErrorStats::add(double err_m) {
  sum_sq_ += err_m * err_m;
  max_ = std::max(max_, err_m);
  ++n_;
}

TrackingStats TrajectoryPilot::ErrorStats::stats() const {
  TrackingStats s;
  s.samples = n_;
  s.rms_m = n_ ? std::sqrt(sum_sq_ / static_cast<double>(n_)) : 0.0;
  s.max_m = max_;
  return s;
}

TrajectoryPilot::TrajectoryPilot(Trajectory trajectory, PilotConfig config)
    : trajectory_(std::move(trajectory)), config_(config) {}

void TrajectoryPilot::on_board_frame(const mavlink::Frame& f) {
  if (f.sysid != config_.target_system) return;
  if (f.is<msg::Heartbeat>()) {
    const auto hb = f.as<msg::Heartbeat>();
    if (hb.autopilot != static_cast<uint8_t>(mavlink::MavAutopilot::Invalid)) {
      armed_ = shows_armed(hb);
      // The mode is set when the board shows it: PX4 SITL acknowledged a DO_SET_MODE as accepted and
      // then said "Switching to Position is currently not available" to the next one.
      const uint32_t mode = hb.custom_mode & 0xFFFF0000u;
      mode_set_ = mode == stick_mode().custom_mode();
      // PX4 ends a takeoff in Hold (AUTO.LOITER); a failsafe out of it (Land, RTL) is no end.
      if (mode == kPx4Takeoff.custom_mode()) takeoff_mode_seen_ = true;
      else if (takeoff_mode_seen_ && armed_ && mode == kPx4Hold.custom_mode()) takeoff_ended_ = true;
    }
  } else if (f.is<msg::SysStatus>()) {
    ready_ = (f.as<msg::SysStatus>().onboard_control_sensors_health & mavlink::sys_status::kPrearmCheck) != 0;
  } else if (f.is<msg::CommandAck>()) {
    const auto a = f.as<msg::CommandAck>();
    if (a.command == mavlink::cmd::kNavTakeoff) takeoff_ack_ = a.result;
  }
}

msg::CommandLong TrajectoryPilot::command(const CommandRequest& request) const {
  const auto& p = request.params;
  msg::CommandLong c;
  c.target_system = config_.target_system;
  c.target_component = config_.target_component;
  c.command = request.command;
  c.param1 = p[0]; c.param2 = p[1]; c.param3 = p[2]; c.param4 = p[3]; c.param5 = p[4]; c.param6 = p[5]; c.param7 = p[6];
  return c;
}

msg::ManualControl manual_control_for(const msg::RcChannelsOverride& rc) {
  const auto centred = [](uint16_t pwm_us) { return static_cast<int16_t>(std::clamp((pwm_us - 1500) * 2, -1000, 1000)); };
  msg::ManualControl m;
  m.target = rc.target_system;
  m.x = centred(rc.chan2_raw);
  m.y = centred(rc.chan1_raw);
  m.z = static_cast<int16_t>(std::clamp(rc.chan3_raw - 1000, 0, 1000));
  m.r = centred(rc.chan4_raw);
  return m;
}

msg::RcChannelsOverride TrajectoryPilot::sticks(double roll, double pitch, double yaw, double throttle) const {
  msg::RcChannelsOverride rc;
  rc.target_system = config_.target_system;
  rc.target_component = config_.target_component;
  rc.chan1_raw = pwm(roll);
  rc.chan2_raw = pwm(pitch);
  rc.chan3_raw = static_cast<uint16_t>(std::lround(1000.0 + 1000.0 * std::clamp(throttle, 0.0, 1.0)));
  rc.chan4_raw = pwm(yaw);
  for (auto* c : {&rc.chan5_raw, &rc.chan6_raw, &rc.chan7_raw, &rc.chan8_raw}) *c = UINT16_MAX;  // untouched
  return rc;
}

void TrajectoryPilot::send_sticks(double t_s, const msg::RcChannelsOverride& rc, PilotOutput& out) {
  last_rc_s_ = t_s;
  out.rc = rc;
  out.manual = manual_control_for(rc);
  last_sticks_ = rc;
}

void TrajectoryPilot::fly_sticks_to(const TrajectoryReference& ref, const PilotPose& pose, double t_s, PilotOutput& out) {
  const double dt_s = last_rc_t_s_ < 0 ? 1.0 / config_.rc_rate_hz : std::clamp(t_s - last_rc_t_s_, 0.0, 0.2);
  last_rc_t_s_ = t_s;
  send_sticks(t_s, config_.mode == StickMode::Attitude ? attitude_sticks(ref, pose, dt_s) : velocity_sticks(ref, pose), out);
}

void TrajectoryPilot::enter(PilotState next, double t_s, PilotOutput& out, const std::string& why) {
  state_ = next;
  state_start_s_ = t_s;
  last_command_s_ = -1e9;
  out.event = std::string("trajectory: ") + to_string(next) + (why.empty() ? "" : " (" + why + ")");
}


void TrajectoryPilot::observe_truth(double t_s, const PilotPose& truth) {
  if (state_ != PilotState::Trajectory) return;
  const auto ref = trajectory_.at(t_s - trajectory_start_s_);
  double err_sq = 0;
  for (std::size_t k = 0; k < 3; ++k) err_sq += (ref.p_ENU_m[k] - truth.p_ENU_m[k]) * (ref.p_ENU_m[k] - truth.p_ENU_m[k]);
  truth_tracking_.add(std::sqrt(err_sq));
}

msg::RcChannelsOverride TrajectoryPilot::velocity_sticks(const TrajectoryReference& ref, const PilotPose& pose) const {
  const auto v = velocity_setpoint(state_ == PilotState::Trajectory, ref, pose, config_.kp_1_s);
  const double c = std::cos(pose.yaw_ENU_rad), s = std::sin(pose.yaw_ENU_rad);
  const double forward = v[0] * c + v[1] * s;  // along the nose
  const double right = v[0] * s - v[1] * c;    // to the right of the nose
  const double dz = config_.stick_deadzone;
  const double climb = stick_for(v[2] >= 0 ? v[2] / config_.max_up_m_s : v[2] / config_.max_down_m_s, dz);
  const double yaw_rate = config_.kp_yaw_1_s * wrap_pi(ref.yaw_ENU_rad - pose.yaw_ENU_rad);  // ENU: CCW +
  return sticks(stick_for(right / config_.max_xy_m_s, dz), stick_for(forward / config_.max_xy_m_s, dz),
                stick_for(-yaw_rate / config_.max_yaw_rate_rad_s, dz), 0.5 + 0.5 * climb);
}

double throttle_for_thrust(double thrust, const PilotConfig& c) {
  const double hover = c.thr_hover;
  const double t = thrust <= hover ? 0.5 * (thrust - c.thr_min) / (hover - c.thr_min)
                                   : 0.5 + 0.5 * (thrust - hover) / (c.thr_max - hover);
  return std::clamp(t, 0.0, 1.0);
}

msg::RcChannelsOverride TrajectoryPilot::attitude_sticks(const TrajectoryReference& ref, const PilotPose& pose, double dt_s) {
  const auto v_sp = velocity_setpoint(state_ == PilotState::Trajectory, ref, pose, config_.kp_1_s);
  const double g = kGravity_m_s2;
  // Horizontal: velocity error -> acceleration -> tilt, limited to what full stick gives.
  double a_e = config_.kv_xy_1_s * (v_sp[0] - pose.v_ENU_m_s[0]);
  double a_n = config_.kv_xy_1_s * (v_sp[1] - pose.v_ENU_m_s[1]);
  const double a_max = g * std::tan(config_.max_tilt_rad);
  if (const double a = std::hypot(a_e, a_n); a > a_max) {
    a_e *= a_max / a;
    a_n *= a_max / a;
  }
  const double c = std::cos(pose.yaw_ENU_rad), s = std::sin(pose.yaw_ENU_rad);
  const double pitch_down_rad = std::atan((a_e * c + a_n * s) / g);  // forward acceleration: nose down
  const double roll_rad = std::atan((a_e * s - a_n * c) / g);        // to the right: roll right
  // Vertical: velocity error -> acceleration, an integrator learns the board's true hover thrust.
  const double e_vz = v_sp[2] - pose.v_ENU_m_s[2];
  hover_integral_ = std::clamp(hover_integral_ + config_.ki_z_1_s2 * e_vz * dt_s, -kMaxHoverCorrection_m_s2, kMaxHoverCorrection_m_s2);
  const double a_up = config_.kv_z_1_s * e_vz + hover_integral_;
  const double thrust = config_.thr_hover * (g + a_up) / g / (std::cos(pitch_down_rad) * std::cos(roll_rad));
  const double yaw_rate = config_.kp_yaw_1_s * wrap_pi(ref.yaw_ENU_rad - pose.yaw_ENU_rad);  // ENU: CCW +
  return sticks(roll_rad / config_.max_tilt_rad, pitch_down_rad / config_.max_tilt_rad,
                std::clamp(-yaw_rate / config_.max_yaw_rate_rad_s, -1.0, 1.0), throttle_for_thrust(thrust, config_));
}

PilotOutput TrajectoryPilot::step(double t_s, const PilotPose& pose) {
  PilotOutput out;
  const double in_state_s = t_s - state_start_s_;
  const bool resend = t_s - last_command_s_ >= 1.0;  // commands are repeated each second until they take
  const double z0 = trajectory_.waypoints().front().p_ENU_m[2];
  if (state_ != PilotState::Trajectory && !finished() && in_state_s > config_.state_timeout_s) {
    failure_ = std::string(to_string(state_)) + " did not complete within " + std::to_string(static_cast<int>(config_.state_timeout_s)) + " s";
    enter(PilotState::Failed, t_s, out, failure_);
    return out;
  }
  switch (state_) {
    case PilotState::Init:
      if (ready_) enter(PilotState::Arm, t_s, out, "the board is ready to arm");
      break;
    case PilotState::Arm:
      if (armed_) {
        enter(PilotState::Takeoff, t_s, out, "armed");
      } else if (resend) {
        out.commands.push_back(command(arm_request()));
        last_command_s_ = t_s;
      }
      break;
    case PilotState::Takeoff: {
      const bool at_height = std::fabs(pose.p_ENU_m[2] - z0) < config_.takeoff_tolerance_m;
      if (!armed_) {
        failure_ = "the board disarmed during takeoff";
        enter(PilotState::Failed, t_s, out, failure_);
      } else if ((at_height || takeoff_ended_) && takeoff_ack_ == 0) {
        // At the height, or the board ended its takeoff short of it (PX4 ends it on its own estimate
        // and its MIS_TAKEOFF_ALT acceptance, and then holds where it is): the sticks fly the rest.
        // Centred sticks first: PX4 takes a manual mode only once its manual control input is
        // valid, which PX4 SITL (MANUAL_CONTROL) judged only after several samples: a second of them.
        if (centred_since_s_ < 0) centred_since_s_ = t_s;
        const bool attitude = config_.mode == StickMode::Attitude;
        if (!mode_set_) {
          if (sticks_due(t_s)) send_sticks(t_s, sticks(0, 0, 0, 0.5), out);
          if (resend && t_s - centred_since_s_ >= kCentredBeforeMode_s) {
            out.commands.push_back(command(set_mode_request(stick_mode())));
            last_command_s_ = t_s;
          }
        } else if (!at_height) {
          // Short of the height in the sticks' mode: they climb to the first waypoint before its
          // clock starts, so the trajectory's tracking starts where the trajectory does.
          if (!short_by_m_) {
            short_by_m_ = z0 - pose.p_ENU_m[2];
            last_rc_t_s_ = -1;
            hover_integral_ = 0;
          }
          const auto first = trajectory_.at(0.0);
          out.reference = first;
          if (sticks_due(t_s)) fly_sticks_to(first, pose, t_s, out);
        } else {
          trajectory_start_s_ = t_s;
          last_rc_t_s_ = -1;
          hover_integral_ = 0;
          enter(PilotState::Trajectory, t_s, out,
                "at " + metres_text(z0) + " m, " + (attitude ? "Stabilized" : "Position") + " mode" +
                    (short_by_m_ ? "; the board ended its takeoff " + metres_text(*short_by_m_) + " m short, the sticks climbed the rest"
                                 : ""));
        }
      } else if (takeoff_ack_ != 0 && resend) {
        out.commands.push_back(command(takeoff_request(config_.home_alt_msl_m + z0)));
        last_command_s_ = t_s;
      }
      break;
    }
    case PilotState::Trajectory:
    case PilotState::Hold: {
      const double tt = t_s - trajectory_start_s_;
      const auto ref = trajectory_.at(tt);
      out.reference = ref;
      if (state_ == PilotState::Trajectory) {
        double err_sq = 0;
        for (std::size_t k = 0; k < 3; ++k) err_sq += (ref.p_ENU_m[k] - pose.p_ENU_m[k]) * (ref.p_ENU_m[k] - pose.p_ENU_m[k]);
        out.tracking_error_m = std::sqrt(err_sq);
        tracking_.add(*out.tracking_error_m);
        if (tt >= trajectory_.duration_s()) enter(PilotState::Hold, t_s, out, "trajectory flown");
      } else if (in_state_s >= config_.hold_s) {
        enter(PilotState::Land, t_s, out);
        break;
      }
      if (sticks_due(t_s)) fly_sticks_to(ref, pose, t_s, out);
      break;
    }
    case PilotState::Land:
      // The last sticks held as they were: the manual control input stays valid (no stick-loss
      // failsafe), and sticks that do not move are no pilot taking over (PX4's COM_RC_OVERRIDE).
      if (armed_ && last_sticks_ && sticks_due(t_s)) send_sticks(t_s, *last_sticks_, out);
      if (!armed_) {
        enter(PilotState::Done, t_s, out, "landed and disarmed");
      } else if (resend) {
        out.commands.push_back(command(land_request()));
        last_command_s_ = t_s;
        if (in_state_s > 30.0) enter(PilotState::Disarm, t_s, out, "no auto-disarm after 30 s");
      }
      break;
    case PilotState::Disarm:
      if (!armed_) enter(PilotState::Done, t_s, out, "disarmed");
      else if (resend) {
        out.commands.push_back(command(disarm_request()));
        last_command_s_ = t_s;
      }
      break;
    case PilotState::Done:
    case PilotState::Failed: break;
  }
  return out;
}

}  // namespace hitl::vehicle
