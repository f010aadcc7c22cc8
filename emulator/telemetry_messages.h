// The telemetry the emulated board streams, as PX4's mavlink module builds it: one pure builder per
// message from the flight state (wire frames NED/FRD, wire units), and the stream table the start
// script configures (spec step 9, PX4's defaults for the rest). The board sends them (streams.cpp).
#pragma once

#include <array>
#include <cstdint>

#include "base/mavlink/messages.h"
#include "emulator/flight_adapter.h"

namespace hitl::target {

/// The messages the board can stream or send on request (SET_MESSAGE_INTERVAL, REQUEST_MESSAGE).
bool stream_known(uint32_t msgid);

/// A default stream: message id and interval.
struct StreamInterval {
  uint32_t msgid = 0;
  int64_t interval_us = 0;
};
/// Every instance's default streams (HEARTBEAT 1 Hz, ATTITUDE 10 Hz, ...); HIL_ACTUATOR_CONTROLS is
/// not among them (only the HIL instance outside lockstep streams it, at the board's actuator rate).
const std::array<StreamInterval, 9>& default_stream_intervals();

/// SYS_STATUS: the sensors present and enabled; healthy but AHRS until the attitude is valid, pre-arm
/// check healthy when ready to arm; a full 4S battery.
mavlink::msg::SysStatus sys_status(const FlightState& s);
mavlink::msg::ExtendedSysState extended_sys_state(const FlightState& s);
/// A full 4S LiPo (16.8 V, 0.5 A), temperature and consumption unknown.
mavlink::msg::BatteryStatus battery_status();
mavlink::msg::Attitude attitude(const FlightState& s, uint32_t time_boot_ms);
mavlink::msg::AttitudeQuaternion attitude_quaternion(const FlightState& s, uint32_t time_boot_ms);
mavlink::msg::LocalPositionNed local_position_ned(const FlightState& s, uint32_t time_boot_ms);
/// lat/lon degE7, altitudes mm, velocities cm/s, heading cdeg 0..35999.
mavlink::msg::GlobalPositionInt global_position_int(const FlightState& s, uint32_t time_boot_ms);
mavlink::msg::HomePosition home_position(const FlightState& s);
mavlink::msg::EstimatorStatus estimator_status(const FlightState& s, uint64_t time_usec);
/// MAVLink 2, COMMAND_INT, bytewise parameters; flight_sw_version says PX4 v1.16 (the dialect it follows).
mavlink::msg::AutopilotVersion autopilot_version();

}  // namespace hitl::target
