// The emulated board's wiring: the HIL and GCS MAVLink instances, the VOXL2's VIO listener, the
// parameter set (the flight core's, then the spec's HITL set as PX4 v1.16 has it), the faults, and
// the loop that polls them and sends what is due. Each side of the board has its own file
// (board_impl.h lists them).
#include "emulator/board.h"

#include <utility>
#include <poll.h>

#include <algorithm>

#include "base/common/clock.h"
#include "emulator/board_impl.h"
#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_file.h"

namespace hitl::target {
namespace {

namespace msg = mavlink::msg;
// The firmware whose parameter set the board follows (the "#absent" notes name firmwares this way).
constexpr const char* kEmulatedFirmware = "PX4 v1.16";
/// The loop waits for input at most this long, so streams and status stay on time.
constexpr uint64_t kMaxWait_us = 5000;

const char* landed_name(mavlink::MavLandedState s) {
  switch (s) {
    case mavlink::MavLandedState::OnGround: return "on_ground";
    case mavlink::MavLandedState::InAir: return "in_air";
    case mavlink::MavLandedState::Takeoff: return "takeoff";
    case mavlink::MavLandedState::Landing: return "landing";
    case mavlink::MavLandedState::Undefined: return "undefined";
  }
  return "?";
}

}  // namespace

std::vector<MavlinkInstance*> Board::Impl::instances() {
  std::vector<MavlinkInstance*> v{hil.get()};
  if (gcs) v.push_back(gcs.get());
  return v;
}

bool Board::Impl::hil_mode() const {
  const auto* p = params.get("SYS_HITL");
  return p && p->i == 1;
}

void Board::Impl::handle_frame(const mavlink::Frame& f, MavlinkInstance& inst) {
  if (f.desc == nullptr) return;
  // A message for another system is not ours (0: broadcast).
  auto for_us = [&](uint8_t target_system) { return target_system == 0 || target_system == config.sysid; };
  switch (f.msgid) {
    case msg::HilSensor::kId: on_hil_sensor(f.as<msg::HilSensor>()); break;
    case msg::HilGps::kId: on_hil_gps(f.as<msg::HilGps>()); break;
    case msg::CommandLong::kId: {
      const auto m = f.as<msg::CommandLong>();
      if (!for_us(m.target_system)) return;
      handle_command(inst, f, m.command, {m.param1, m.param2, m.param3, m.param4, m.param5, m.param6, m.param7});
      break;
    }
    case msg::CommandInt::kId: {
      const auto m = f.as<msg::CommandInt>();
      if (!for_us(m.target_system)) return;
      handle_command(inst, f, m.command,
                     {m.param1, m.param2, m.param3, m.param4, static_cast<float>(m.x), static_cast<float>(m.y), m.z});
      break;
    }
    case msg::ParamRequestList::kId:
      for (std::size_t i = 0; i < params.size(); ++i) send_param(inst, i);
      break;
    case msg::ParamRequestRead::kId: on_param_request_read(inst, f.as<msg::ParamRequestRead>()); break;
    case msg::ParamSet::kId: on_param_set(inst, f.as<msg::ParamSet>()); break;
    case msg::SerialControl::kId:
      for (const auto& reply : shell->on_serial_control(f.as<msg::SerialControl>())) inst.send(reply);
      break;
    case msg::Timesync::kId: on_timesync(inst, f); break;
    case msg::RcChannelsOverride::kId: {
      const auto m = f.as<msg::RcChannelsOverride>();
      if (!for_us(m.target_system)) return;
      flight->on_rc_override({m.chan1_raw, m.chan2_raw, m.chan3_raw, m.chan4_raw, m.chan5_raw, m.chan6_raw,
                              m.chan7_raw, m.chan8_raw},
                             now_us);
      break;
    }
    case msg::ManualControl::kId: {
      const auto m = f.as<msg::ManualControl>();
      if (!for_us(m.target)) return;
      on_manual_control(m);
      break;
    }
    default: break;
  }
}

void Board::Impl::measure_vio_rate() {
  const double t_s = monotonic_s();
  if (t_s - vio_rate_since_s < 0.5) return;
  vio_rate_hz = static_cast<double>(odometry_received - vio_rate_count) / (t_s - vio_rate_since_s);
  vio_rate_since_s = t_s;
  vio_rate_count = odometry_received;
}

void Board::Impl::drain_vio() {
  if (!vio) return;
  while (auto d = vio->receive())
    vio_parser->parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
      if (f.is<msg::Odometry>()) ++odometry_received;  // decoded as voxl-hitl-vio-server does; counted
    });
}

BoardSnapshot Board::Impl::make_snapshot() const {
  BoardSnapshot s;
  const auto st = flight->state();
  s.board_time_s = static_cast<double>(now_us) * 1e-6;
  s.armed = st.armed;
  s.mode = st.mode_name;
  s.landed_state = landed_name(st.landed);
  s.estimator_ready = st.ready_to_arm;
  s.not_ready_reason = st.not_ready_reason;
  s.altitude_m = -st.p_NED_m[2];
  s.hil_sensor_received = hil_sensor_received;
  s.hil_gps_received = hil_gps_received;
  s.odometry_received = odometry_received;
  s.actuators_sent = actuators_sent;
  s.commands_received = commands_received;
  s.params_set = params_set;
  s.shell_commands = shell ? shell->commands_run() : 0;
  s.malformed = hil->parser_stats().crc_errors + hil->parser_stats().parse_errors + hil->parser_stats().truncated;
  if (gcs) s.malformed += gcs->parser_stats().crc_errors + gcs->parser_stats().parse_errors + gcs->parser_stats().truncated;
  if (vio_parser) s.malformed += vio_parser->stats().crc_errors + vio_parser->stats().parse_errors;
  s.hil_partner = hil->partner() ? hil->partner()->to_string() : "";
  s.gcs_partner = gcs && gcs->partner() ? gcs->partner()->to_string() : "";
  s.dsp_hitl_status = dsp.status_text();
  return s;
}

void Board::Impl::publish() {
  measure_vio_rate();
  auto s = make_snapshot();
  std::lock_guard<std::mutex> lock(snapshot_mutex);
  published = std::move(s);
}

Expected<std::unique_ptr<Board>> Board::create(const BoardConfig& config) {
  auto impl = std::make_unique<Impl>();
  impl->config = config;
  impl->vio_rate_since_s = monotonic_s();
  // The flight core's own parameters first, then the spec's HITL set: its values win where both name one.
  // The board follows PX4 v1.16: a parameter of the set that v1.16 does not have (hitl-defaults.params'
  // "#absent NAME | PX4 v1.16 | ..." lines) is not added, so `hitl params check` sees it absent.
  impl->flight = std::make_unique<FlightAdapter>(impl->params);
  for (const auto& p : vehicle::hitl_default_params()) {
    if (const auto* note = vehicle::find_absent_note(p.name); note != nullptr && note->firmware == kEmulatedFirmware) continue;
    if (impl->params.get(p.name) == nullptr) impl->params.add(p.name, p.value);
    else if (auto set = impl->params.set(p.name, p.value); !set) return Error{"HITL default " + p.name + ": " + set.error().message};
  }
  // --fault (faults.h): parameters as a misconfigured board has them, and a disagreeing GPS.
  if (config.faults.sys_hitl_0) (void)impl->params.set("SYS_HITL", vehicle::ParamValue::int32(0));
  if (config.faults.wrong_cal_acc0_id) (void)impl->params.set("CAL_ACC0_ID", vehicle::ParamValue::int32(kWrongAccelDeviceId));
  if (config.faults.ekf_not_converging) impl->flight->inject_mag_swing(kEkfFaultMagSwing_rad);
  auto bound = [&config](uint16_t port) { return config.os_picks_ports ? uint16_t{0} : port; };
  auto hil = MavlinkInstance::open("HIL instance (--hil-port)", config.bind_address, bound(config.hil_port), impl->messages,
                                   config.sysid, config.compid);
  if (!hil) return hil.error();
  impl->hil = std::move(hil.value());
  if (config.gcs_port != 0) {
    auto gcs = MavlinkInstance::open("GCS instance (--gcs-port)", config.bind_address, bound(config.gcs_port), impl->messages,
                                     config.sysid, config.compid);
    if (!gcs) return gcs.error();
    impl->gcs = std::move(gcs.value());
  }
  if (config.vio_port != 0 && !config.faults.no_vio_listener) {
    net::UdpEndpoint::Config c;
    c.name = "VIO listener (--vio-port)";
    c.bind_address = config.bind_address;
    c.bind_port = bound(config.vio_port);
    auto ep = net::UdpEndpoint::open(c);
    if (!ep) return ep.error();
    impl->vio.emplace(std::move(ep.value()));
    impl->vio_parser.emplace(impl->messages);
  }
  impl->default_streams(*impl->hil, true);
  if (impl->gcs) impl->default_streams(*impl->gcs, false);
  Impl* raw = impl.get();
  impl->shell.emplace([raw](const std::string& line) { return raw->shell_command(line); });
  impl->dsp.start();  // the start script: qshell dsp_hitl start
  return std::unique_ptr<Board>(new Board(std::move(impl)));
}

Board::Board(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Board::~Board() = default;

BoardPorts Board::ports() const {
  BoardPorts p;
  p.hil_port = impl_->hil->port();
  if (impl_->gcs) p.gcs_port = impl_->gcs->port();
  if (impl_->vio) p.vio_port = impl_->vio->local_address().port();
  return p;
}

std::string Board::describe() const {
  std::string out = "HIL instance on UDP " + std::to_string(impl_->hil->port());
  if (impl_->gcs) out += ", GCS instance on UDP " + std::to_string(impl_->gcs->port());
  if (impl_->vio) out += ", VIO listener on UDP " + std::to_string(impl_->vio->local_address().port());
  out += impl_->config.lockstep ? " (lockstep: the board's clock is HIL_SENSOR.time_usec)" : "";
  if (impl_->config.faults.any()) out += "; FAULTS INJECTED: " + impl_->config.faults.names();
  return out;
}

Expected<Board::EndReason> Board::run(const std::atomic<bool>& stop, Observer& observer) {
  Impl& s = *impl_;
  s.start_us = monotonic_us();
  uint64_t next_status_us = 1000000;
  bool announced = false;
  while (!stop.load()) {
    const bool wall_clock = s.on_wall_clock();
    if (wall_clock) s.now_us = monotonic_us() - s.start_us;
    if (s.config.duration_s > 0 && static_cast<double>(s.now_us) * 1e-6 >= s.config.duration_s) return EndReason::Duration;
    // Wait for input until the next thing is due (at most kMaxWait_us).
    pollfd fds[3];
    nfds_t n = 0;
    fds[n++] = {s.hil->fd(), POLLIN, 0};
    if (s.gcs) fds[n++] = {s.gcs->fd(), POLLIN, 0};
    if (s.vio) fds[n++] = {s.vio->fd(), POLLIN, 0};
    int timeout_ms = static_cast<int>(kMaxWait_us / 1000);
    if (wall_clock) {
      const uint64_t next = std::min(s.split.next_due_us(), s.now_us + kMaxWait_us);
      timeout_ms = static_cast<int>(next > s.now_us ? (next - s.now_us + 999) / 1000 : 0);
    }
    // Lockstep: hitl sim sends the next HIL_SENSOR within microseconds of the answer; poll for it
    // a moment before sleeping (bounded and adaptive: an idle session costs nothing).
    if (s.config.lockstep) {
      if (!s.busy_poll.spin({fds, n}) && ::poll(fds, n, timeout_ms) == 0) s.busy_poll.on_nothing();
    } else {
      ::poll(fds, n, timeout_ms);
    }
    if (s.on_wall_clock()) s.now_us = monotonic_us() - s.start_us;
    auto handler = [&](const mavlink::Frame& f, MavlinkInstance& inst) { s.handle_frame(f, inst); };
    s.hil->poll(handler);
    if (s.gcs) s.gcs->poll(handler);
    s.drain_vio();
    if (!announced && (s.hil->partner() || (s.gcs && s.gcs->partner()))) {
      announced = true;
      s.statustext("hitl target: an emulated VOXL2 board, not PX4", mavlink::MavSeverity::Notice);
      observer.on_event({Severity::Info, "first MAVLink partner: " + (s.hil->partner() ? s.hil->partner()->to_string() : s.gcs->partner()->to_string())});
    }
    if (auto text = s.lockstep_clock.take_new_session_text()) observer.on_event({Severity::Info, *text});
    if (!s.config.lockstep) s.process_board(s.now_us);
    for (auto* inst : s.instances())
      for (uint32_t id : inst->due_streams(static_cast<int64_t>(s.now_us))) s.send_stream(*inst, id);
    s.send_owed_answers();  // lockstep: last, after everything the same input caused (board_impl.h)
    if (s.now_us >= next_status_us) {
      next_status_us += 1000000;
      s.publish();
      observer.on_status(snapshot());
    }
  }
  s.publish();
  return EndReason::Stopped;
}

BoardSnapshot Board::snapshot() const {
  std::lock_guard<std::mutex> lock(impl_->snapshot_mutex);
  return impl_->published;
}

}  // namespace hitl::target
