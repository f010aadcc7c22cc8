// The emulated board's command side, as PX4's commander and mavlink modules answer: COMMAND_LONG /
// COMMAND_INT (arm, takeoff, land, mode, message intervals and requests) with COMMAND_ACK and a
// STATUSTEXT that says why, the parameter protocol, TIMESYNC and MANUAL_CONTROL sticks.
#include <algorithm>
#include <cmath>

#include "base/common/clock.h"
#include "base/mavlink/text_field.h"
#include "emulator/board_impl.h"
#include "emulator/telemetry_messages.h"
#include "engine/vehicle/params_file.h"

namespace hitl::target {

namespace msg = mavlink::msg;
using mavlink::MavResult;

void Board::Impl::ack(MavlinkInstance& inst, uint16_t command, MavResult result, const mavlink::Frame& from) {
  msg::CommandAck a;
  a.command = command;
  a.result = static_cast<uint8_t>(result);
  a.target_system = from.sysid;
  a.target_component = from.compid;
  inst.send(a);
}

void Board::Impl::handle_command(MavlinkInstance& inst, const mavlink::Frame& f, uint16_t command,
                                 const std::array<float, 7>& p) {
  ++commands_received;
  CommandResult r{MavResult::Unsupported, ""};
  switch (command) {
    case mavlink::cmd::kComponentArmDisarm: {
      const bool force = std::fabs(p[1] - mavlink::cmd::kArmDisarmForceMagic) < 0.5f;
      r = p[0] > 0.5f ? flight->arm(force, now_us) : flight->disarm(force, now_us);
      break;
    }
    case mavlink::cmd::kNavTakeoff: r = flight->takeoff(p[6], now_us); break;
    case mavlink::cmd::kNavLand: r = flight->land(now_us); break;
    case mavlink::cmd::kDoSetMode:
      r = flight->set_mode(static_cast<uint8_t>(p[1]), static_cast<uint8_t>(p[2]), now_us);
      break;
    case mavlink::cmd::kSetMessageInterval: {
      const auto id = static_cast<uint32_t>(p[0]);
      if (!stream_known(id)) {
        r = {MavResult::Unsupported, ""};
      } else {
        const float interval = p[1];
        if (interval < 0) inst.set_interval_us(id, 0);
        else if (interval == 0) default_streams(inst, &inst == hil.get());
        else inst.set_interval_us(id, static_cast<int64_t>(interval));
        r = {MavResult::Accepted, ""};
      }
      break;
    }
    case mavlink::cmd::kRequestMessage:
    case mavlink::cmd::kRequestAutopilotCapabilities: {
      const auto id = command == mavlink::cmd::kRequestMessage ? static_cast<uint32_t>(p[0]) : msg::AutopilotVersion::kId;
      if (!stream_known(id)) {
        r = {MavResult::Unsupported, ""};
      } else {
        ack(inst, command, MavResult::Accepted, f);
        send_stream(inst, id);
        return;
      }
      break;
    }
    default: break;
  }
  ack(inst, command, r.result, f);
  say_flight_messages();  // a denial's words, once, with the flight stack's severity
}

void Board::Impl::send_param(MavlinkInstance& inst, std::size_t index) {
  const auto& p = params.at(index);
  msg::ParamValue v;
  mavlink::set_text(v.param_id, p.name);
  v.param_value = vehicle::encode_param_float(p.value);
  v.param_type = static_cast<uint8_t>(p.value.type);
  v.param_count = static_cast<uint16_t>(params.size());
  v.param_index = static_cast<uint16_t>(index);
  inst.send(v);
}

void Board::Impl::on_param_request_read(MavlinkInstance& inst, const msg::ParamRequestRead& m) {
  std::optional<std::size_t> index;
  if (m.param_index >= 0) {
    if (static_cast<std::size_t>(m.param_index) < params.size()) index = static_cast<std::size_t>(m.param_index);
  } else {
    index = params.index_of(mavlink::text_of(m.param_id));
  }
  if (index) send_param(inst, *index);
}

void Board::Impl::on_param_set(MavlinkInstance& inst, const msg::ParamSet& m) {
  const std::string name = mavlink::text_of(m.param_id);
  const auto index = params.index_of(name);
  if (!index) {
    statustext("param set: unknown parameter " + name, mavlink::MavSeverity::Error);
    return;
  }
  const auto type = m.param_type == mavlink::kMavParamTypeInt32 ? vehicle::ParamType::Int32 : vehicle::ParamType::Real32;
  auto set = params.set(name, vehicle::decode_param_float(m.param_value, type));
  if (set) ++params_set;
  else statustext("param set: " + set.error().message, mavlink::MavSeverity::Error);
  send_param(inst, *index);  // PX4 answers with the value it now has, set or not
}

void Board::Impl::on_timesync(MavlinkInstance& inst, const mavlink::Frame& f) {
  // PX4's Timesync: a request (tc1 0) is answered with our clock in tc1.
  const auto m = f.as<msg::Timesync>();
  if (m.tc1 != 0) return;
  msg::Timesync reply;
  reply.tc1 = static_cast<int64_t>(monotonic_us()) * 1000;
  reply.ts1 = m.ts1;
  reply.target_system = f.sysid;
  reply.target_component = f.compid;
  inst.send(reply);
}

void Board::Impl::on_manual_control(const msg::ManualControl& m) {
  // MANUAL_CONTROL: x forward, y right, z thrust 0..1000, r clockwise, each -1000..1000.
  flight->on_sticks(m.y / 1000.0, m.x / 1000.0, m.r / 1000.0, std::clamp(m.z / 1000.0, 0.0, 1.0), now_us);
}

}  // namespace hitl::target
