// The emulated board's telemetry side: the streams each instance sends when due, HEARTBEAT as PX4
// sends it, HIL_ACTUATOR_CONTROLS (the board's 200 Hz stream, or one answer per HIL_SENSOR in
// lockstep) and STATUSTEXT. The messages themselves are built in telemetry_messages.cpp.
#include "base/contract/hil_actuators.h"
#include "base/mavlink/heartbeat.h"
#include "base/mavlink/severity.h"
#include "base/mavlink/text_field.h"
#include "emulator/board_impl.h"
#include "emulator/telemetry_messages.h"

namespace hitl::target {

namespace msg = mavlink::msg;

uint8_t Board::Impl::base_mode_with_hil(const FlightState& s) const {
  return static_cast<uint8_t>(s.base_mode | (hil_mode() ? mavlink::mode_flag::kHilEnabled : 0));
}

void Board::Impl::say_flight_messages() {
  for (const auto& m : flight->take_messages()) statustext(m.text, mavlink::mav_severity(m.severity));
}

void Board::Impl::statustext(const std::string& text, mavlink::MavSeverity severity) {
  for (const auto& st : statustext_chunker.split(static_cast<uint8_t>(severity), text))
    for (auto* i : instances()) i->send(st);
}

void Board::Impl::send_stream(MavlinkInstance& inst, uint32_t id) {
  const auto s = flight->state();
  switch (id) {
    case msg::Heartbeat::kId: inst.send(mavlink::px4_quadrotor_heartbeat(base_mode_with_hil(s), s.custom_mode, s.armed)); break;
    case msg::SysStatus::kId: inst.send(sys_status(s)); break;
    case msg::ExtendedSysState::kId: inst.send(extended_sys_state(s)); break;
    case msg::BatteryStatus::kId: inst.send(battery_status()); break;
    case msg::Attitude::kId: inst.send(attitude(s, boot_ms())); break;
    case msg::AttitudeQuaternion::kId: inst.send(attitude_quaternion(s, boot_ms())); break;
    case msg::LocalPositionNed::kId:
      if (s.local_valid) inst.send(local_position_ned(s, boot_ms()));
      break;
    case msg::GlobalPositionInt::kId:
      if (s.global_valid) inst.send(global_position_int(s, boot_ms()));
      break;
    case msg::HomePosition::kId:
      if (s.home_set) inst.send(home_position(s));
      break;
    case msg::EstimatorStatus::kId: inst.send(estimator_status(s, now_us)); break;
    case msg::HilActuatorControls::kId: send_actuators(inst); break;
    case msg::AutopilotVersion::kId: inst.send(autopilot_version()); break;
    default: break;
  }
}

void Board::Impl::send_actuators(MavlinkInstance& inst) {
  if (config.faults.no_actuators) return;  // --fault no-actuators
  inst.send(actuator_message());
  ++actuators_sent;
}

msg::HilActuatorControls Board::Impl::actuator_message() const {
  const auto s = flight->state();
  msg::HilActuatorControls m;
  // Lockstep: stamped with the HIL_SENSOR it answers, as PX4 SITL stamps it with its lockstep
  // clock (the simulator matches answers to steps by it); otherwise the board's own clock.
  m.time_usec = config.lockstep && lockstep_clock.started() ? lockstep_clock.last_sensor_time_us() : now_us;
  for (std::size_t i = 0; i < 4; ++i) m.controls[i] = s.armed ? static_cast<float>(motors[i]) : 0.0f;
  m.mode = base_mode_with_hil(s);
  m.flags = config.faults.wrong_flags ? kWrongActuatorFlags : kVoxl2ActuatorFlags;
  return m;
}

void Board::Impl::default_streams(MavlinkInstance& inst, bool is_hil) {
  for (const auto& stream : default_stream_intervals()) inst.set_interval_us(stream.msgid, stream.interval_us);
  if (is_hil && !config.lockstep)
    inst.set_interval_us(msg::HilActuatorControls::kId, static_cast<int64_t>(config.actuator_interval_us));
}

}  // namespace hitl::target
