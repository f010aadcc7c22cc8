#include "emulator/board.h"

#include "base/common/clock.h"
#include <poll.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <optional>
#include <sstream>

#include "base/contract/dsp_hitl_status.h"
#include "base/mavlink/enums.h"
#include "base/mavlink/frame_parser.h"
#include "base/mavlink/messages.h"
#include "emulator/flight_adapter.h"
#include "emulator/mavlink_instance.h"
#include "emulator/param_store.h"
#include "emulator/shell.h"
#include "engine/net/udp_endpoint.h"
#include "engine/vehicle/param_notes.h"
#include "engine/vehicle/params_file.h"
#include "target/core/dsp_hitl.h"
#include "target/core/hil_gps.h"
#include "target/core/hil_split.h"

namespace hitl::target {
namespace {

namespace msg = mavlink::msg;
// The firmware whose parameter set the board follows (the "#absent" notes name firmwares this way).
constexpr const char* kEmulatedFirmware = "PX4 v1.16";
using mavlink::MavResult;

constexpr int64_t hz(double rate) { return static_cast<int64_t>(1e6 / rate); }

/// MAVLink text fields (STATUSTEXT.text, PARAM_VALUE.param_id) need no terminating NUL when full.
template <std::size_t N>
void copy_text(std::array<char, N>& field, const std::string& text) {
  field.fill('\0');
  std::memcpy(field.data(), text.data(), std::min(N, text.size()));
}

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

struct Board::Impl {
  BoardConfig config;
  mavlink::MessageSet messages = mavlink::MessageSet::compiled();
  std::unique_ptr<MavlinkInstance> hil;
  std::unique_ptr<MavlinkInstance> gcs;
  std::optional<net::UdpEndpoint> vio;
  std::optional<mavlink::FrameParser> vio_parser;
  ParamStore params;
  std::unique_ptr<FlightAdapter> flight;
  HilSplit split;
  DspHitl dsp;
  std::optional<Shell> shell;

  uint64_t start_us = 0;
  uint64_t now_us = 0;        ///< board time since start
  bool sensor_time_started = false;
  uint64_t sensor_time_origin_us = 0;
  uint64_t sensor_time_base_us = 0;
  uint64_t last_sensor_time_us = 0;   ///< the last HIL_SENSOR.time_usec (lockstep answers echo it)
  uint64_t sim_sessions = 0;          ///< lockstep: simulator sessions seen (time_usec went back: a new one)
  uint64_t hil_sensor_received = 0, hil_gps_received = 0, odometry_received = 0, actuators_sent = 0;
  uint64_t commands_received = 0, params_set = 0;
  std::array<double, 4> motors{};
  double vio_rate_hz = 0, vio_rate_since_s = 0;
  uint64_t vio_rate_count = 0;

  mutable std::mutex snapshot_mutex;
  BoardSnapshot published;

  std::vector<MavlinkInstance*> instances() {
    std::vector<MavlinkInstance*> v{hil.get()};
    if (gcs) v.push_back(gcs.get());
    return v;
  }

  bool hil_mode() const {
    const auto* p = params.get("SYS_HITL");
    return p && p->i == 1;
  }

  uint32_t boot_ms() const { return static_cast<uint32_t>(now_us / 1000); }

  /// HEARTBEAT.base_mode: the flight stack's flags, plus HIL when SYS_HITL is 1 (as commander does).
  uint8_t base_mode_with_hil(const FlightState& s) const {
    return static_cast<uint8_t>(s.base_mode | (hil_mode() ? mavlink::mode_flag::kHilEnabled : 0));
  }

  // --- outgoing --------------------------------------------------------------------------------
  void statustext(const std::string& text, mavlink::MavSeverity severity) {
    msg::Statustext st;
    st.severity = static_cast<uint8_t>(severity);
    copy_text(st.text, text);
    for (auto* i : instances()) i->send(st);
  }

  msg::Heartbeat heartbeat() const {
    const auto s = flight->state();
    msg::Heartbeat hb;
    hb.type = static_cast<uint8_t>(mavlink::MavType::Quadrotor);
    hb.autopilot = static_cast<uint8_t>(mavlink::MavAutopilot::Px4);
    hb.base_mode = base_mode_with_hil(s);
    hb.custom_mode = s.custom_mode;
    hb.system_status = static_cast<uint8_t>(s.armed ? mavlink::MavState::Active : mavlink::MavState::Standby);
    hb.mavlink_version = mavlink::kMavlinkVersion;
    return hb;
  }

  void send_stream(MavlinkInstance& inst, uint32_t id) {
    const auto s = flight->state();
    switch (id) {
      case msg::Heartbeat::kId: inst.send(heartbeat()); break;
      case msg::SysStatus::kId: {
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
        inst.send(m);
        break;
      }
      case msg::ExtendedSysState::kId: {
        msg::ExtendedSysState m;
        m.landed_state = static_cast<uint8_t>(s.landed);
        inst.send(m);
        break;
      }
      case msg::BatteryStatus::kId: {
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
        inst.send(m);
        break;
      }
      case msg::Attitude::kId: {
        msg::Attitude m;
        m.time_boot_ms = boot_ms();
        m.roll = static_cast<float>(s.roll_rad);
        m.pitch = static_cast<float>(s.pitch_rad);
        m.yaw = static_cast<float>(s.yaw_rad);
        m.rollspeed = static_cast<float>(s.w_FRD_rad_s[0]);
        m.pitchspeed = static_cast<float>(s.w_FRD_rad_s[1]);
        m.yawspeed = static_cast<float>(s.w_FRD_rad_s[2]);
        inst.send(m);
        break;
      }
      case msg::AttitudeQuaternion::kId: {
        msg::AttitudeQuaternion m;
        m.time_boot_ms = boot_ms();
        m.q1 = static_cast<float>(s.q_FRD_to_NED[0]);
        m.q2 = static_cast<float>(s.q_FRD_to_NED[1]);
        m.q3 = static_cast<float>(s.q_FRD_to_NED[2]);
        m.q4 = static_cast<float>(s.q_FRD_to_NED[3]);
        m.rollspeed = static_cast<float>(s.w_FRD_rad_s[0]);
        m.pitchspeed = static_cast<float>(s.w_FRD_rad_s[1]);
        m.yawspeed = static_cast<float>(s.w_FRD_rad_s[2]);
        inst.send(m);
        break;
      }
      case msg::LocalPositionNed::kId: {
        if (!s.local_valid) break;
        msg::LocalPositionNed m;
        m.time_boot_ms = boot_ms();
        m.x = static_cast<float>(s.p_NED_m[0]);
        m.y = static_cast<float>(s.p_NED_m[1]);
        m.z = static_cast<float>(s.p_NED_m[2]);
        m.vx = static_cast<float>(s.v_NED_m_s[0]);
        m.vy = static_cast<float>(s.v_NED_m_s[1]);
        m.vz = static_cast<float>(s.v_NED_m_s[2]);
        inst.send(m);
        break;
      }
      case msg::GlobalPositionInt::kId: {
        if (!s.global_valid) break;
        msg::GlobalPositionInt m;
        m.time_boot_ms = boot_ms();
        m.lat = static_cast<int32_t>(std::llround(s.lat_deg * 1e7));
        m.lon = static_cast<int32_t>(std::llround(s.lon_deg * 1e7));
        m.alt = static_cast<int32_t>(std::llround(s.alt_msl_m * 1000));
        m.relative_alt = static_cast<int32_t>(std::llround(-s.p_NED_m[2] * 1000));
        m.vx = static_cast<int16_t>(std::lround(s.v_NED_m_s[0] * 100));
        m.vy = static_cast<int16_t>(std::lround(s.v_NED_m_s[1] * 100));
        m.vz = static_cast<int16_t>(std::lround(s.v_NED_m_s[2] * 100));
        double hdg = std::fmod(s.yaw_rad * 180.0 / M_PI + 360.0, 360.0);
        m.hdg = static_cast<uint16_t>(std::lround(hdg * 100) % 36000);
        inst.send(m);
        break;
      }
      case msg::HomePosition::kId: {
        if (!s.home_set) break;
        msg::HomePosition m;
        m.latitude = static_cast<int32_t>(std::llround(s.home_lat_deg * 1e7));
        m.longitude = static_cast<int32_t>(std::llround(s.home_lon_deg * 1e7));
        m.altitude = static_cast<int32_t>(std::llround(s.home_alt_msl_m * 1000));
        m.q = {1, 0, 0, 0};
        inst.send(m);
        break;
      }
      case msg::EstimatorStatus::kId: {
        msg::EstimatorStatus m;
        m.time_usec = now_us;
        m.flags = s.estimator_flags;
        m.vel_ratio = static_cast<float>(s.vel_ratio);
        m.pos_horiz_ratio = static_cast<float>(s.pos_horiz_ratio);
        m.pos_vert_ratio = static_cast<float>(s.pos_vert_ratio);
        m.mag_ratio = static_cast<float>(s.mag_ratio);
        m.pos_horiz_accuracy = static_cast<float>(s.pos_horiz_accuracy_m);
        m.pos_vert_accuracy = static_cast<float>(s.pos_vert_accuracy_m);
        inst.send(m);
        break;
      }
      case msg::HilActuatorControls::kId: send_actuators(inst); break;
      case msg::AutopilotVersion::kId: {
        msg::AutopilotVersion m;
        m.capabilities = mavlink::capability::kCommandInt | mavlink::capability::kParamEncodeBytewise |
                         mavlink::capability::kMavlink2;
        m.flight_sw_version = (1u << 24) | (16u << 16);  // reports PX4 v1.16 compatibility; this is an emulator
        m.vendor_id = 0;
        m.product_id = 0;
        inst.send(m);
        break;
      }
      default: break;
    }
  }

  void send_actuators(MavlinkInstance& inst) {
    if (config.faults.no_actuators) return;  // --fault no-actuators
    const auto s = flight->state();
    msg::HilActuatorControls m;
    // Lockstep: stamped with the HIL_SENSOR it answers, as PX4 SITL stamps it with its lockstep
    // clock (the simulator matches answers to steps by it); otherwise the board's own clock.
    m.time_usec = config.lockstep && sensor_time_started ? last_sensor_time_us : now_us;
    for (std::size_t i = 0; i < 4; ++i) m.controls[i] = s.armed ? static_cast<float>(motors[i]) : 0.0f;
    m.mode = base_mode_with_hil(s);
    m.flags = config.faults.wrong_flags ? kWrongActuatorFlags : 0x0F;  // the VOXL2's quad bitmask (spec)
    inst.send(m);
    ++actuators_sent;
  }

  bool streams_known(uint32_t id) const {
    switch (id) {
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

  void default_streams(MavlinkInstance& inst, bool is_hil) {
    // The start script's stream configuration (spec step 9) and PX4's defaults for the rest.
    inst.set_interval_us(msg::Heartbeat::kId, hz(1));
    inst.set_interval_us(msg::SysStatus::kId, hz(1));
    inst.set_interval_us(msg::ExtendedSysState::kId, hz(1));
    inst.set_interval_us(msg::BatteryStatus::kId, hz(0.5));
    inst.set_interval_us(msg::Attitude::kId, hz(10));
    inst.set_interval_us(msg::GlobalPositionInt::kId, hz(5));
    inst.set_interval_us(msg::LocalPositionNed::kId, hz(5));
    inst.set_interval_us(msg::EstimatorStatus::kId, hz(1));
    inst.set_interval_us(msg::HomePosition::kId, hz(0.5));
    if (is_hil && !config.lockstep) inst.set_interval_us(msg::HilActuatorControls::kId, static_cast<int64_t>(config.actuator_interval_us));
  }

  // --- incoming --------------------------------------------------------------------------------
  void ack(MavlinkInstance& inst, uint16_t command, MavResult result, const mavlink::Frame& from) {
    msg::CommandAck a;
    a.command = command;
    a.result = static_cast<uint8_t>(result);
    a.target_system = from.sysid;
    a.target_component = from.compid;
    inst.send(a);
  }

  void handle_command(MavlinkInstance& inst, const mavlink::Frame& f, uint16_t command, const std::array<float, 7>& p) {
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
        if (!streams_known(id)) {
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
        if (!streams_known(id)) {
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
    if (!r.text.empty())
      statustext(r.text, r.result == MavResult::Accepted ? mavlink::MavSeverity::Info : mavlink::MavSeverity::Critical);
  }

  void send_param(MavlinkInstance& inst, std::size_t index) {
    const auto& p = params.at(index);
    msg::ParamValue v;
    copy_text(v.param_id, p.name);
    v.param_value = vehicle::encode_param_float(p.value);
    v.param_type = static_cast<uint8_t>(p.value.type);
    v.param_count = static_cast<uint16_t>(params.size());
    v.param_index = static_cast<uint16_t>(index);
    inst.send(v);
  }

  static std::string param_name(const std::array<char, 16>& id) {
    std::size_t n = 0;
    while (n < id.size() && id[n] != '\0') ++n;
    return std::string(id.data(), n);
  }

  void handle_frame(const mavlink::Frame& f, MavlinkInstance& inst) {
    if (f.desc == nullptr) return;
    switch (f.msgid) {
      case msg::HilSensor::kId: {
        const auto m = f.as<msg::HilSensor>();
        ++hil_sensor_received;
        if (config.lockstep) advance_sensor_clock(m.time_usec);
        HilSensorInput in;
        in.time_usec = m.time_usec;
        in.accel_FRD_m_s2[0] = m.xacc; in.accel_FRD_m_s2[1] = m.yacc; in.accel_FRD_m_s2[2] = m.zacc;
        in.gyro_FRD_rad_s[0] = m.xgyro; in.gyro_FRD_rad_s[1] = m.ygyro; in.gyro_FRD_rad_s[2] = m.zgyro;
        in.mag_FRD_gauss[0] = m.xmag; in.mag_FRD_gauss[1] = m.ymag; in.mag_FRD_gauss[2] = m.zmag;
        in.abs_pressure_hPa = m.abs_pressure;
        in.diff_pressure_hPa = m.diff_pressure;
        in.pressure_alt_m = m.pressure_alt;
        in.temperature_degC = m.temperature;
        in.fields_updated = m.fields_updated;
        in.id = m.id;
        split.on_hil_sensor(in, now_us);
        if (config.lockstep) {
          process_board(now_us);
          send_actuators(*hil);  // one answer per HIL_SENSOR, as PX4 SITL's lockstep does
        }
        break;
      }
      case msg::HilGps::kId: {
        const auto m = f.as<msg::HilGps>();
        ++hil_gps_received;
        HilGpsInput in;
        in.time_usec = m.time_usec;
        in.fix_type = m.fix_type;
        in.lat_degE7 = m.lat;
        in.lon_degE7 = m.lon;
        in.alt_mm = m.alt;
        in.eph_cm = m.eph;
        in.epv_cm = m.epv;
        in.vel_cm_s = m.vel;
        in.vn_cm_s = m.vn;
        in.ve_cm_s = m.ve;
        in.vd_cm_s = m.vd;
        in.cog_cdeg = m.cog;
        in.satellites_visible = m.satellites_visible;
        in.id = m.id;
        flight->on_gps(to_sensor_gps(in, now_us));
        break;
      }
      case msg::CommandLong::kId: {
        const auto m = f.as<msg::CommandLong>();
        if (m.target_system != 0 && m.target_system != config.sysid) return;
        handle_command(inst, f, m.command, {m.param1, m.param2, m.param3, m.param4, m.param5, m.param6, m.param7});
        break;
      }
      case msg::CommandInt::kId: {
        const auto m = f.as<msg::CommandInt>();
        if (m.target_system != 0 && m.target_system != config.sysid) return;
        handle_command(inst, f, m.command,
                       {m.param1, m.param2, m.param3, m.param4, static_cast<float>(m.x), static_cast<float>(m.y), m.z});
        break;
      }
      case msg::ParamRequestList::kId:
        for (std::size_t i = 0; i < params.size(); ++i) send_param(inst, i);
        break;
      case msg::ParamRequestRead::kId: {
        const auto m = f.as<msg::ParamRequestRead>();
        std::optional<std::size_t> index;
        if (m.param_index >= 0) {
          if (static_cast<std::size_t>(m.param_index) < params.size()) index = static_cast<std::size_t>(m.param_index);
        } else {
          index = params.index_of(param_name(m.param_id));
        }
        if (index) send_param(inst, *index);
        break;
      }
      case msg::ParamSet::kId: {
        const auto m = f.as<msg::ParamSet>();
        const std::string name = param_name(m.param_id);
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
        break;
      }
      case msg::SerialControl::kId:
        for (const auto& reply : shell->on_serial_control(f.as<msg::SerialControl>())) inst.send(reply);
        break;
      case msg::Timesync::kId: {  // PX4's Timesync: a request (tc1 0) is answered with our clock in tc1
        const auto m = f.as<msg::Timesync>();
        if (m.tc1 != 0) break;
        msg::Timesync reply;
        reply.tc1 = static_cast<int64_t>(monotonic_us()) * 1000;
        reply.ts1 = m.ts1;
        reply.target_system = f.sysid;
        reply.target_component = f.compid;
        inst.send(reply);
        break;
      }
      case msg::RcChannelsOverride::kId: {
        const auto m = f.as<msg::RcChannelsOverride>();
        if (m.target_system != 0 && m.target_system != config.sysid) return;
        flight->on_rc_override({m.chan1_raw, m.chan2_raw, m.chan3_raw, m.chan4_raw, m.chan5_raw, m.chan6_raw,
                                m.chan7_raw, m.chan8_raw},
                               now_us);
        break;
      }
      case msg::ManualControl::kId: {
        const auto m = f.as<msg::ManualControl>();
        if (m.target != 0 && m.target != config.sysid) return;
        // MANUAL_CONTROL: x forward, y right, z thrust 0..1000, r clockwise, each -1000..1000.
        flight->on_sticks(m.y / 1000.0, m.x / 1000.0, m.r / 1000.0, std::clamp(m.z / 1000.0, 0.0, 1.0), now_us);
        break;
      }
      default: break;
    }
  }

  /// Lockstep: the board's clock follows HIL_SENSOR.time_usec from the first one on, continuing
  /// from the wall-clock time it had until then (so HEARTBEATs flow before the simulator starts).
  /// A time_usec lower than the last one is a new simulator session (each starts again near 0):
  /// the board re-anchors, its own clock carrying on from where it was, as it did for the first.
  void advance_sensor_clock(uint64_t time_usec) {
    if (!sensor_time_started || time_usec < last_sensor_time_us) {
      if (sensor_time_started) {
        ++sim_sessions;
        new_session_text = "lockstep: a new simulator session (HIL_SENSOR.time_usec went back from " +
                           std::to_string(last_sensor_time_us / 1000) + " ms to " + std::to_string(time_usec / 1000) +
                           " ms); the board's clock carries on from " + std::to_string(now_us / 1000) + " ms";
      }
      sensor_time_started = true;
      sensor_time_origin_us = time_usec;
      sensor_time_base_us = now_us;
    }
    last_sensor_time_us = time_usec;
    now_us = std::max(now_us, sensor_time_base_us + (time_usec - sensor_time_origin_us) + 4000);
  }
  std::string new_session_text;  ///< said by run() (it holds the observer), then cleared

  // --- the board's own processing ----------------------------------------------------------------
  void process_board(uint64_t t_us) {
    auto out = split.poll(t_us);
    if (config.faults.dsp_hitl_stalled && dsp.counters().hil_imu_received >= kDspStallAfterImu) out = {};  // --fault: MUORB stops delivering
    if (out.imu) {
      if (auto s = dsp.on_imu(*out.imu, t_us)) {
        flight->on_imu(s->accel, s->gyro);
        motors = flight->step(t_us);
      }
    }
    if (out.mag_baro) {
      const auto s = dsp.on_mag_baro(*out.mag_baro, t_us);
      if (s.mag) flight->on_mag(*s.mag);
      if (s.baro) flight->on_baro(*s.baro);
    }
    for (const auto& text : flight->take_messages()) statustext(text, mavlink::MavSeverity::Info);
  }

  /// voxl-hitl-vio-server's ODOMETRY rate (wall clock, as the real server measures it), per status.
  void measure_vio_rate() {
    const double t_s = monotonic_s();
    if (t_s - vio_rate_since_s < 0.5) return;
    vio_rate_hz = static_cast<double>(odometry_received - vio_rate_count) / (t_s - vio_rate_since_s);
    vio_rate_since_s = t_s;
    vio_rate_count = odometry_received;
  }

  void drain_vio() {
    if (!vio) return;
    while (auto d = vio->receive())
      vio_parser->parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
        if (f.is<msg::Odometry>()) ++odometry_received;  // decoded as voxl-hitl-vio-server does; counted
      });
  }

  ShellResult shell_command(const std::string& line);

  /// The apps processor's `voxl-hitl-vio-server --status [--json]` (target/vio-server), which the
  /// emulated board answers in its one shell: its VIO listener is that server.
  std::string vio_server_status(bool json) const {
    char buf[256];
    if (!vio) {
      const char* why = "voxl-hitl-vio-server is not running (hitl target: no VIO listener)";
      if (json) std::snprintf(buf, sizeof buf, "{\"running\":false,\"error\":\"%s\"}\n", why);
      else std::snprintf(buf, sizeof buf, "%s\n", why);
      return buf;
    }
    const std::string listen = vio->local_address().to_string();
    if (json)
      std::snprintf(buf, sizeof buf, "{\"running\":true,\"listen\":\"%s\",\"odometry_rate_hz\":%.1f,\"odometry\":%llu}\n",
                    listen.c_str(), vio_rate_hz, static_cast<unsigned long long>(odometry_received));
    else
      std::snprintf(buf, sizeof buf, "voxl-hitl-vio-server (emulated by hitl target): listening on UDP %s\n  ODOMETRY:  %.1f Hz, %llu received\n",
                    listen.c_str(), vio_rate_hz, static_cast<unsigned long long>(odometry_received));
    return buf;
  }

  BoardSnapshot make_snapshot() const {
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

  void publish() {
    measure_vio_rate();
    auto s = make_snapshot();
    std::lock_guard<std::mutex> lock(snapshot_mutex);
    published = std::move(s);
  }
};

ShellResult Board::Impl::shell_command(const std::string& line) {
  std::string cmd = line;
  if (cmd.rfind("qshell ", 0) == 0) cmd = cmd.substr(7);  // on the board qshell runs it on the DSP
  if (cmd == "help")
    return "Builtin commands (hitl target, an emulated VOXL2 board, not PX4):\n"
           "  dsp_hitl start | stop | status (also through qshell)\n  commander status | check | arm | disarm | takeoff | land\n"
           "  ekf2 status\n  mavlink status\n  param show [PATTERN] | param set NAME VALUE\n  ver all\n  help\n"
           "  voxl-hitl-vio-server --status [--json]   (the apps processor's VIO server)\n";
  // dsp_hitl as target/px4's module: status of a stopped module prints "Running: no" with zero
  // counters and returns 1; stop of a stopped module does nothing (ModuleBase).
  if (cmd == "dsp_hitl status")
    return dsp.running() ? ShellResult{dsp.status_text()} : ShellResult{dsp_hitl_status_text(false, {}, {}), 1};
  if (cmd == "dsp_hitl stop") {
    if (dsp.running()) dsp.stop();
    return {};
  }
  if (cmd == "dsp_hitl start") {
    if (dsp.running()) return {"dsp_hitl: already running\n", 1};
    dsp.start();
    return {};
  }
  if (cmd == "commander status") return flight->commander_status();
  if (cmd == "commander check") return flight->commander_check();
  if (cmd.rfind("voxl-hitl-vio-server --status", 0) == 0) return vio_server_status(cmd.find("--json") != std::string::npos);
  if (cmd == "ekf2 status") return flight->ekf2_status();
  if (cmd == "ver all") return "HW arch: VOXL2 (M0197), emulated by hitl target\nFW version: hitl target (PX4 v1.16 dialect)\n";
  if (cmd == "mavlink status") {
    std::string out;
    for (auto* i : instances()) {
      out += "instance #" + std::string(i == hil.get() ? "0" : "2") + " (" + i->name() + "):\n";
      out += "\tUDP (" + std::to_string(i->port()) + ", remote port: " +
             (i->partner() ? std::to_string(i->partner()->port()) : std::string("none")) + ")\n";
      out += "\tpartner: " + (i->partner() ? i->partner()->to_string() : std::string("none yet")) + "\n";
      out += "\trx: " + std::to_string(i->stats().frames_in) + " messages, tx: " + std::to_string(i->stats().frames_out) + " messages\n";
    }
    return out;
  }
  auto result_text = [](const CommandResult& r, const char* what) {
    return r.result == MavResult::Accepted ? std::string(what) + ": ok\n" : (r.text.empty() ? std::string(what) + ": denied" : r.text) + "\n";
  };
  if (cmd == "commander arm") return result_text(flight->arm(false, now_us), "arm");
  if (cmd == "commander arm -f") return result_text(flight->arm(true, now_us), "arm");
  if (cmd == "commander disarm") return result_text(flight->disarm(false, now_us), "disarm");
  if (cmd == "commander takeoff") return result_text(flight->takeoff(NAN, now_us), "takeoff");
  if (cmd == "commander land") return result_text(flight->land(now_us), "land");
  if (cmd.rfind("param show", 0) == 0) {
    std::string pattern = cmd.size() > 11 ? cmd.substr(11) : "";
    const bool prefix = !pattern.empty() && pattern.back() == '*';
    if (prefix) pattern.pop_back();
    std::string out;
    for (std::size_t i = 0; i < params.size(); ++i) {
      const auto& p = params.at(i);
      if (!pattern.empty() && (prefix ? p.name.rfind(pattern, 0) != 0 : p.name != pattern)) continue;
      out += p.name + " [" + std::to_string(i) + "]: " + p.value.to_string() + "\n";
    }
    return out.empty() ? "no parameter matches\n" : out;
  }
  if (cmd.rfind("param set ", 0) == 0) {
    std::istringstream ss(cmd.substr(10));
    std::string name, value;
    ss >> name >> value;
    const auto* current = params.get(name);
    if (current == nullptr) return {"Parameter " + name + " not found.\n", 1};  // PX4's param returns 1
    try {
      auto v = current->type == vehicle::ParamType::Int32 ? vehicle::ParamValue::int32(std::stoi(value))
                                                          : vehicle::ParamValue::real32(std::stof(value));
      auto r = params.set(name, v);
      if (!r) return {"param set: " + r.error().message + "\n", 1};
      ++params_set;
      return name + ": " + v.to_string() + "\n";
    } catch (const std::exception&) {
      return {"param set: '" + value + "' is not a number\n", 1};
    }
  }
  // A command the board has, with a verb it does not know (or `a; b`, which this shell does not
  // split): the module's usage and return 1, as PX4's ModuleBase does, not "command not found".
  const std::string name = cmd.substr(0, cmd.find(' '));
  for (const char* known : {"dsp_hitl", "commander", "ekf2", "mavlink", "param", "ver"}) {
    if (name == known)
      return {name + ": unknown command '" + (cmd.size() > name.size() ? cmd.substr(name.size() + 1) : std::string()) +
                  "' (one command per line; help lists what this shell runs)\n",
              1};
  }
  return "nsh: " + line.substr(0, line.find(' ')) + ": command not found\n";
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
  auto hil = MavlinkInstance::open("HIL instance (--hil-port)", config.bind_address, config.hil_port, impl->messages,
                                   config.sysid, config.compid);
  if (!hil) return hil.error();
  impl->hil = std::move(hil.value());
  if (config.gcs_port != 0) {
    auto gcs = MavlinkInstance::open("GCS instance (--gcs-port)", config.bind_address, config.gcs_port, impl->messages,
                                     config.sysid, config.compid);
    if (!gcs) return gcs.error();
    impl->gcs = std::move(gcs.value());
  }
  if (config.vio_port != 0 && !config.faults.no_vio_listener) {
    net::UdpEndpoint::Config c;
    c.name = "VIO listener (--vio-port)";
    c.bind_address = config.bind_address;
    c.bind_port = config.vio_port;
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
    const bool wall_clock = !s.config.lockstep || !s.sensor_time_started;
    if (wall_clock) s.now_us = monotonic_us() - s.start_us;
    if (s.config.duration_s > 0 && static_cast<double>(s.now_us) * 1e-6 >= s.config.duration_s) return EndReason::Duration;
    // Wait for input until the next thing is due (at most 5 ms).
    pollfd fds[3];
    nfds_t n = 0;
    fds[n++] = {s.hil->fd(), POLLIN, 0};
    if (s.gcs) fds[n++] = {s.gcs->fd(), POLLIN, 0};
    if (s.vio) fds[n++] = {s.vio->fd(), POLLIN, 0};
    int timeout_ms = 5;
    if (wall_clock) {
      const uint64_t next = std::min(s.split.next_due_us(), s.now_us + 5000);
      timeout_ms = static_cast<int>(next > s.now_us ? (next - s.now_us + 999) / 1000 : 0);
    }
    ::poll(fds, n, timeout_ms);
    if (!s.config.lockstep || !s.sensor_time_started) s.now_us = monotonic_us() - s.start_us;
    auto handler = [&](const mavlink::Frame& f, MavlinkInstance& inst) { s.handle_frame(f, inst); };
    s.hil->poll(handler);
    if (s.gcs) s.gcs->poll(handler);
    s.drain_vio();
    if (!announced && (s.hil->partner() || (s.gcs && s.gcs->partner()))) {
      announced = true;
      s.statustext("hitl target: an emulated VOXL2 board, not PX4", mavlink::MavSeverity::Notice);
      observer.on_event({false, "first MAVLink partner: " + (s.hil->partner() ? s.hil->partner()->to_string() : s.gcs->partner()->to_string())});
    }
    if (!s.new_session_text.empty()) {
      observer.on_event({false, s.new_session_text});
      s.new_session_text.clear();
    }
    if (!s.config.lockstep) s.process_board(s.now_us);
    for (auto* inst : s.instances())
      for (uint32_t id : inst->due_streams(static_cast<int64_t>(s.now_us))) s.send_stream(*inst, id);
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
