#include "engine/telemetry/vehicle_telemetry.h"

#include <cmath>
#include <limits>

#include "base/mavlink/enums.h"
#include "base/mavlink/messages.h"
#include "engine/telemetry/px4_mode.h"

namespace hitl::telemetry {
namespace {
namespace msg = mavlink::msg;
}

EstimatorStatusValues estimator_status_from(const mavlink::Frame& f) {
  const auto m = f.as<msg::EstimatorStatus>();
  EstimatorStatusValues e;
  e.flags = m.flags;
  e.vel_ratio = m.vel_ratio;
  e.pos_horiz_ratio = m.pos_horiz_ratio;
  e.pos_vert_ratio = m.pos_vert_ratio;
  e.mag_ratio = m.mag_ratio;
  e.hagl_ratio = m.hagl_ratio;
  e.tas_ratio = m.tas_ratio;
  e.pos_horiz_accuracy_m = m.pos_horiz_accuracy;
  e.pos_vert_accuracy_m = m.pos_vert_accuracy;
  return e;
}

std::string landed_state_name(uint8_t landed_state) {
  switch (static_cast<mavlink::MavLandedState>(landed_state)) {
    case mavlink::MavLandedState::Undefined: return "undefined";
    case mavlink::MavLandedState::OnGround: return "on ground";
    case mavlink::MavLandedState::InAir: return "in air";
    case mavlink::MavLandedState::Takeoff: return "taking off";
    case mavlink::MavLandedState::Landing: return "landing";
  }
  return "state " + std::to_string(landed_state);
}

void VehicleTelemetryTracker::on_frame(const mavlink::Frame& f, double now_s) {
  if (f.desc == nullptr) return;
  VehicleTelemetry& s = state_;
  switch (f.msgid) {
    case msg::Heartbeat::kId: {
      const auto hb = f.as<msg::Heartbeat>();
      if (hb.autopilot == static_cast<uint8_t>(mavlink::MavAutopilot::Invalid)) return;  // a GCS or the simulator
      s.heartbeat = true;
      s.armed = (hb.base_mode & mavlink::mode_flag::kSafetyArmed) != 0;
      s.mode = px4_mode_name(hb.base_mode, hb.custom_mode);
      s.system_status = hb.system_status;
      break;
    }
    case msg::ExtendedSysState::kId: {
      const auto m = f.as<msg::ExtendedSysState>();
      s.landed = landed_state_name(m.landed_state);
      const auto l = static_cast<mavlink::MavLandedState>(m.landed_state);
      s.in_air = l == mavlink::MavLandedState::InAir || l == mavlink::MavLandedState::Takeoff ||
                 l == mavlink::MavLandedState::Landing;
      break;
    }
    case msg::SysStatus::kId: {
      const auto m = f.as<msg::SysStatus>();
      if ((m.onboard_control_sensors_present & mavlink::sys_status::kPrearmCheck) != 0)
        s.ready_to_arm = (m.onboard_control_sensors_health & mavlink::sys_status::kPrearmCheck) != 0;
      if (!battery_status_heard_) {
        if (m.voltage_battery != std::numeric_limits<uint16_t>::max()) s.battery_V = m.voltage_battery / 1000.0;
        if (m.current_battery >= 0) s.battery_A = m.current_battery / 100.0;
        if (m.battery_remaining >= 0) s.battery_remaining_pct = m.battery_remaining;
      }
      break;
    }
    case msg::BatteryStatus::kId: {
      const auto m = f.as<msg::BatteryStatus>();
      battery_status_heard_ = true;
      double mV = 0;
      bool any = false;
      for (const uint16_t cell : m.voltages)
        if (cell != std::numeric_limits<uint16_t>::max()) {
          mV += cell;
          any = true;
        }
      if (any) s.battery_V = mV / 1000.0;
      if (m.current_battery >= 0) s.battery_A = m.current_battery / 100.0;
      else s.battery_A.reset();
      if (m.battery_remaining >= 0) s.battery_remaining_pct = m.battery_remaining;
      else s.battery_remaining_pct.reset();
      break;
    }
    case msg::EstimatorStatus::kId: s.estimator = estimator_status_from(f); break;
    case msg::LocalPositionNed::kId: {
      const auto m = f.as<msg::LocalPositionNed>();
      s.p_NED_m = std::array<double, 3>{m.x, m.y, m.z};
      s.v_NED_m_s = std::array<double, 3>{m.vx, m.vy, m.vz};
      break;
    }
    case msg::AttitudeQuaternion::kId: {
      const auto m = f.as<msg::AttitudeQuaternion>();
      s.q_FRD_to_NED = std::array<double, 4>{m.q1, m.q2, m.q3, m.q4};
      break;
    }
    case msg::GlobalPositionInt::kId:
      s.relative_alt_m = f.as<msg::GlobalPositionInt>().relative_alt / 1000.0;
      break;
    default: return;
  }
  s.last_heard_s[f.msgid] = now_s;
}

}  // namespace hitl::telemetry
