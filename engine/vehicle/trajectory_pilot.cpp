#include "engine/vehicle/trajectory_pilot.h"

#include <algorithm>
#include <cmath>

#include "engine/mavlink/enums.h"

namespace hitl::vehicle {
namespace {

namespace msg = mavlink::msg;
constexpr uint8_t kPx4MainModePosctl = 3;

/// The stick that asks PX4's position mode for `fraction` of full rate: past the deadzone, which PX4
/// cuts out and rescales (MPC_HOLD_DZ), so small corrections are not swallowed.
double stick_for(double fraction, double deadzone) {
  if (fraction == 0.0) return 0.0;
  const double f = std::clamp(std::fabs(fraction), 0.0, 1.0);
  return std::copysign(deadzone + (1.0 - deadzone) * f, fraction);
}

uint16_t pwm(double stick) { return static_cast<uint16_t>(std::lround(1500.0 + 500.0 * std::clamp(stick, -1.0, 1.0))); }

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

TrajectoryPilot::TrajectoryPilot(Trajectory trajectory, PilotConfig config)
    : trajectory_(std::move(trajectory)), config_(config) {}

void TrajectoryPilot::on_board_frame(const mavlink::Frame& f) {
  if (f.sysid != config_.target_system) return;
  if (f.is<msg::Heartbeat>()) {
    const auto hb = f.as<msg::Heartbeat>();
    if (hb.autopilot != static_cast<uint8_t>(mavlink::MavAutopilot::Invalid))
      armed_ = (hb.base_mode & mavlink::mode_flag::kSafetyArmed) != 0;
  } else if (f.is<msg::SysStatus>()) {
    ready_ = (f.as<msg::SysStatus>().onboard_control_sensors_health & mavlink::sys_status::kPrearmCheck) != 0;
  } else if (f.is<msg::CommandAck>()) {
    const auto a = f.as<msg::CommandAck>();
    if (a.command == mavlink::cmd::kNavTakeoff) takeoff_ack_ = a.result;
    if (a.command == mavlink::cmd::kDoSetMode && a.result == static_cast<uint8_t>(mavlink::MavResult::Accepted)) mode_set_ = true;
  }
}

msg::CommandLong TrajectoryPilot::command(uint16_t id, std::array<float, 7> p) const {
  msg::CommandLong c;
  c.target_system = config_.target_system;
  c.target_component = config_.target_component;
  c.command = id;
  c.param1 = p[0]; c.param2 = p[1]; c.param3 = p[2]; c.param4 = p[3]; c.param5 = p[4]; c.param6 = p[5]; c.param7 = p[6];
  return c;
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

void TrajectoryPilot::enter(PilotState next, double t_s, PilotOutput& out, const std::string& why) {
  state_ = next;
  state_start_s_ = t_s;
  last_command_s_ = -1e9;
  out.event = std::string("trajectory: ") + to_string(next) + (why.empty() ? "" : " (" + why + ")");
}

TrackingStats TrajectoryPilot::tracking() const {
  TrackingStats s;
  s.samples = samples_;
  s.rms_m = samples_ ? std::sqrt(sum_sq_ / static_cast<double>(samples_)) : 0.0;
  s.max_m = max_err_;
  return s;
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
        out.commands.push_back(command(mavlink::cmd::kComponentArmDisarm, {1, 0, 0, 0, 0, 0, 0}));
        last_command_s_ = t_s;
      }
      break;
    case PilotState::Takeoff:
      if (!armed_) {
        failure_ = "the board disarmed during takeoff";
        enter(PilotState::Failed, t_s, out, failure_);
      } else if (std::fabs(pose.p_ENU_m[2] - z0) < config_.takeoff_tolerance_m && takeoff_ack_ == 0) {
        if (!mode_set_ && resend) {
          out.commands.push_back(command(mavlink::cmd::kDoSetMode, {1, kPx4MainModePosctl, 0, 0, 0, 0, 0}));
          last_command_s_ = t_s;
        }
        if (mode_set_) {
          trajectory_start_s_ = t_s;
          enter(PilotState::Trajectory, t_s, out, "at " + std::to_string(z0).substr(0, 4) + " m, Position mode");
        }
      } else if (takeoff_ack_ != 0 && resend) {
        out.commands.push_back(command(mavlink::cmd::kNavTakeoff, {0, 0, 0, NAN, NAN, NAN, static_cast<float>(config_.home_alt_msl_m + z0)}));
        last_command_s_ = t_s;
      }
      break;
    case PilotState::Trajectory:
    case PilotState::Hold: {
      const double tt = t_s - trajectory_start_s_;
      const auto ref = trajectory_.at(tt);
      std::array<double, 3> v{};
      double err_sq = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        const double e = ref.p_ENU_m[k] - pose.p_ENU_m[k];
        err_sq += e * e;
        v[k] = (state_ == PilotState::Trajectory ? ref.v_ENU_m_s[k] : 0.0) + config_.kp_1_s * e;
      }
      if (state_ == PilotState::Trajectory) {
        sum_sq_ += err_sq;
        max_err_ = std::max(max_err_, std::sqrt(err_sq));
        ++samples_;
        if (tt >= trajectory_.duration_s()) enter(PilotState::Hold, t_s, out, "trajectory flown");
      } else if (in_state_s >= config_.hold_s) {
        enter(PilotState::Land, t_s, out);
        break;
      }
      if (t_s - last_rc_s_ >= 1.0 / config_.rc_rate_hz) {
        last_rc_s_ = t_s;
        const double c = std::cos(pose.yaw_ENU_rad), s = std::sin(pose.yaw_ENU_rad);
        const double forward = v[0] * c + v[1] * s;  // along the nose
        const double right = v[0] * s - v[1] * c;    // to the right of the nose
        const double up = v[2];
        const double dz = config_.stick_deadzone;
        const double climb = stick_for(up >= 0 ? up / config_.max_up_m_s : up / config_.max_down_m_s, dz);
        const double yaw_rate = config_.kp_yaw_1_s * wrap_pi(ref.yaw_ENU_rad - pose.yaw_ENU_rad);  // ENU: CCW +
        out.rc = sticks(stick_for(right / config_.max_xy_m_s, dz), stick_for(forward / config_.max_xy_m_s, dz),
                        stick_for(-yaw_rate / config_.max_yaw_rate_rad_s, dz), 0.5 + 0.5 * climb);
      }
      break;
    }
    case PilotState::Land:
      if (!armed_) {
        enter(PilotState::Done, t_s, out, "landed and disarmed");
      } else if (resend) {
        out.commands.push_back(command(mavlink::cmd::kNavLand, {0, 0, 0, NAN, NAN, NAN, NAN}));
        last_command_s_ = t_s;
        if (in_state_s > 30.0) enter(PilotState::Disarm, t_s, out, "no auto-disarm after 30 s");
      }
      break;
    case PilotState::Disarm:
      if (!armed_) enter(PilotState::Done, t_s, out, "disarmed");
      else if (resend) {
        out.commands.push_back(command(mavlink::cmd::kComponentArmDisarm, {0, 0, 0, 0, 0, 0, 0}));
        last_command_s_ = t_s;
      }
      break;
    case PilotState::Done:
    case PilotState::Failed: break;
  }
  return out;
}

}  // namespace hitl::vehicle
