#include "emulator/telemetry_messages.h"

#include <cmath>

#include "base/mavlink/enums.h"
#include "base/mavlink/wire_units.h"

namespace hitl::target {

namespace msg = mavlink::msg;
namespace wire = mavlink::wire;

namespace {
constexpr int64_t period_us(double rate_hz) { return static_cast<int64_t>(1e6 / rate_hz); }

/// ATTITUDE and ATTITUDE_QUATERNION: body rates, FRD.
template <class M>
void set_body_rates(M& m, const FlightState& s) {
  m.rollspeed = static_cast<float>(s.w_FRD_rad_s[0]);
  m.pitchspeed = static_cast<float>(s.w_FRD_rad_s[1]);
  m.yawspeed = static_cast<float>(s.w_FRD_rad_s[2]);
}
}  // namespace

bool stream_known(uint32_t msgid) {
  switch (msgid) {
    case msg::Heartbeat::kId:
    case msg::SysStatus::kId:
    case msg::ExtendedSysState::kId:
    case msg::BatteryStatus::kId:
    case msg::Attitude::kId:
    case msg::AttitudeQuaternion::kId:
    case msg::LocalPositionNed::kId:
    case msg::GlobalPositionInt::kId:
    case msg::HomePosition::kId:
    case msg::EstimatorStatus::kId:
    case msg::HilActuatorControls::kId:
    case msg::AutopilotVersion::kId: return true;
    default: return false;
  }
}

const std::array<StreamInterval, 9>& default_stream_intervals() {
  static const std::array<StreamInterval, 9> table{{
      {msg::Heartbeat::kId, period_us(1)},
      {msg::SysStatus::kId, period_us(1)},
      {msg::ExtendedSysState::kId, period_us(1)},
      {msg::BatteryStatus::kId, period_us(0.5)},
      {msg::Attitude::kId, period_us(10)},
      {msg::GlobalPositionInt::kId, period_us(5)},
      {msg::LocalPositionNed::kId, period_us(5)},
      {msg::EstimatorStatus::kId, period_us(1)},
      {msg::HomePosition::kId, period_us(0.5)},
  }};
  return table;
}

msg::SysStatus sys_status(const FlightState& s) {
  namespace b = mavlink::sys_status;
  msg::SysStatus m;
  const uint32_t present = b::kGyro | b::kAccel | b::kMag | b::kAbsolutePressure | b::kGps | b::kAhrs |
                           b::kMotorOutputs | b::kBattery | b::kPrearmCheck;
  m.onboard_control_sensors_present = present;
  m.onboard_control_sensors_enabled = present;
  uint32_t health = present & ~b::kPrearmCheck;
  if (!s.attitude_valid) health &= ~b::kAhrs;
  if (s.ready_to_arm) health |= b::kPrearmCheck;
  m.onboard_control_sensors_health = health;
  m.voltage_battery = 16800;
  m.current_battery = 500;
  m.battery_remaining = 100;
  m.load = 200;
  return m;
}

msg::ExtendedSysState extended_sys_state(const FlightState& s) {
  msg::ExtendedSysState m;
  m.landed_state = static_cast<uint8_t>(s.landed);
  return m;
}

msg::BatteryStatus battery_status() {
  msg::BatteryStatus m;
  m.id = 0;
  m.type = 1;  // MAV_BATTERY_TYPE_LIPO
  m.temperature = INT16_MAX;
  m.voltages.fill(UINT16_MAX);
  for (int c = 0; c < 4; ++c) m.voltages[static_cast<std::size_t>(c)] = 4200;  // 16.8 V over 4 cells
  m.current_battery = 500;
  m.current_consumed = -1;
  m.energy_consumed = -1;
  m.battery_remaining = 100;
  return m;
}

msg::Attitude attitude(const FlightState& s, uint32_t time_boot_ms) {
  msg::Attitude m;
  m.time_boot_ms = time_boot_ms;
  m.roll = static_cast<float>(s.roll_rad);
  m.pitch = static_cast<float>(s.pitch_rad);
  m.yaw = static_cast<float>(s.yaw_rad);
  set_body_rates(m, s);
  return m;
}

msg::AttitudeQuaternion attitude_quaternion(const FlightState& s, uint32_t time_boot_ms) {
  msg::AttitudeQuaternion m;
  m.time_boot_ms = time_boot_ms;
  m.q1 = static_cast<float>(s.q_FRD_to_NED[0]);
  m.q2 = static_cast<float>(s.q_FRD_to_NED[1]);
  m.q3 = static_cast<float>(s.q_FRD_to_NED[2]);
  m.q4 = static_cast<float>(s.q_FRD_to_NED[3]);
  set_body_rates(m, s);
  return m;
}

msg::LocalPositionNed local_position_ned(const FlightState& s, uint32_t time_boot_ms) {
  msg::LocalPositionNed m;
  m.time_boot_ms = time_boot_ms;
  m.x = static_cast<float>(s.p_NED_m[0]);
  m.y = static_cast<float>(s.p_NED_m[1]);
  m.z = static_cast<float>(s.p_NED_m[2]);
  m.vx = static_cast<float>(s.v_NED_m_s[0]);
  m.vy = static_cast<float>(s.v_NED_m_s[1]);
  m.vz = static_cast<float>(s.v_NED_m_s[2]);
  return m;
}

msg::GlobalPositionInt global_position_int(const FlightState& s, uint32_t time_boot_ms) {
  msg::GlobalPositionInt m;
  m.time_boot_ms = time_boot_ms;
  m.lat = wire::deg_to_degE7(s.lat_deg);
  m.lon = wire::deg_to_degE7(s.lon_deg);
  m.alt = wire::m_to_mm(s.alt_msl_m);
  m.relative_alt = wire::m_to_mm(-s.p_NED_m[2]);
  m.vx = wire::m_s_to_cm_s(s.v_NED_m_s[0]);
  m.vy = wire::m_s_to_cm_s(s.v_NED_m_s[1]);
  m.vz = wire::m_s_to_cm_s(s.v_NED_m_s[2]);
  m.hdg = wire::deg_to_cdeg(s.yaw_rad * 180.0 / M_PI);
  return m;
}

msg::HomePosition home_position(const FlightState& s) {
  msg::HomePosition m;
  m.latitude = wire::deg_to_degE7(s.home_lat_deg);
  m.longitude = wire::deg_to_degE7(s.home_lon_deg);
  m.altitude = wire::m_to_mm(s.home_alt_msl_m);
  m.q = {1, 0, 0, 0};
  return m;
}

msg::EstimatorStatus estimator_status(const FlightState& s, uint64_t time_usec) {
  msg::EstimatorStatus m;
  m.time_usec = time_usec;
  m.flags = s.estimator_flags;
  m.vel_ratio = static_cast<float>(s.vel_ratio);
  m.pos_horiz_ratio = static_cast<float>(s.pos_horiz_ratio);
  m.pos_vert_ratio = static_cast<float>(s.pos_vert_ratio);
  m.mag_ratio = static_cast<float>(s.mag_ratio);
  m.pos_horiz_accuracy = static_cast<float>(s.pos_horiz_accuracy_m);
  m.pos_vert_accuracy = static_cast<float>(s.pos_vert_accuracy_m);
  return m;
}

msg::AutopilotVersion autopilot_version() {
  msg::AutopilotVersion m;
  m.capabilities =
      mavlink::capability::kCommandInt | mavlink::capability::kParamEncodeBytewise | mavlink::capability::kMavlink2;
  m.flight_sw_version = (1u << 24) | (16u << 16);  // reports PX4 v1.16 compatibility; this is an emulator
  m.vendor_id = 0;
  m.product_id = 0;
  return m;
}

}  // namespace hitl::target
